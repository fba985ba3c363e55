"""Fuzz the flow inputs of ``fretwear simulate`` and the assessment's technique models (issue
29, point 5).

Flow: the shipped bundle description (examples/bundle/bundle_geometry.toml) mutated byte by byte
(cuts, flips, NULs, BOMs, nasty tokens), and the same description with one key given a value of
another type or an extreme one, read by :func:`fretwear.flow.description.read_description`;
a description that reads has its first tube's modal forces built
(:func:`fretwear.flow.bundle.tube_forces`: modes, flow, spectrum, synthesis). Assessment:
:class:`~fretwear.assessment.SizingModel` and :class:`~fretwear.assessment.LogisticPOD` built
from odd parameters and evaluated at odd depths, and :func:`~fretwear.assessment.bundle_risk`
with odd probabilities. Only fretwear errors may come out, no example may last over 20 s, no
numpy warning (an overflow is a silent inf in the making), and what is returned holds no NaN or
inf where a number is required. Derandomized; FRETWEAR_FUZZ_SCALE scales the examples.
"""

from __future__ import annotations

import datetime
import itertools
import math
import tomllib
from pathlib import Path

import numpy as np
from fuzzhelpers import examples, mutated, only_fretwear, workdir
from hypothesis import given, settings
from hypothesis import strategies as st
from test_fuzz_manifests_inspections import _toml_value

from fretwear.assessment import (
    LogisticPOD,
    SizingModel,
    bundle_risk,
    inspection_sample,
    plugging_list,
)
from fretwear.flow.bundle import tube_forces
from fretwear.flow.description import read_description

DESCRIPTION = Path(__file__).parents[2] / "examples" / "bundle" / "bundle_geometry.toml"
_COUNTER = itertools.count()

#: values of the wrong type or out of range, as TOML gives them
ODD = st.one_of(
    st.text(max_size=8), st.integers(-10**400, 10**400), st.sampled_from([0, -1, 1, 2**63]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-300, 1e300, 5e-324, 1e9, 1e-9]), st.booleans(),
    st.dates(), st.just(datetime.datetime(2024, 1, 1, 12, 0)),
    st.lists(st.one_of(st.floats(), st.text(max_size=3), st.integers(-5, 5)), max_size=3),
    st.dictionaries(st.sampled_from(["distribution", "median", "sigma_ln", "a"]),
                    st.one_of(st.integers(-3, 3), st.text(max_size=3), st.floats()),
                    max_size=3))


def deterministic(n: int) -> settings:
    """The suite's budget (:func:`fuzzhelpers.examples`), always derandomized."""
    return settings(examples(n), derandomize=True)


def _file(data: bytes) -> Path:
    path = workdir() / f"fuzz-flow-{next(_COUNTER)}.toml"
    path.write_bytes(data)
    return path


def _write(raw: dict) -> bytes:
    """A description dict as TOML: top-level keys, tables, arrays of tables (one level)."""
    head, body = [], []
    for key, value in raw.items():
        if isinstance(value, dict):
            body.append(f"[{key}]")
            for k, v in value.items():
                if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
                    continue
                body.append(f'"{k}" = {_toml_value(v)}')
            for k, v in value.items():
                if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
                    for item in v:
                        body.append(f"[[{key}.{k}]]")
                        body += [f'"{a}" = {_toml_value(b)}' for a, b in item.items()]
        elif isinstance(value, list) and value and all(isinstance(x, dict) for x in value):
            for item in value:
                body.append(f"[[{key}]]")
                body += [f'"{a}" = {_toml_value(b)}' for a, b in item.items()]
        else:
            head.append(f'"{key}" = {_toml_value(value)}')
    return ("\n".join(head + body) + "\n").encode()


def _places(raw: dict) -> list[tuple]:
    """Every key of the description as a path of keys and indices."""
    out = []
    for key, value in raw.items():
        if isinstance(value, dict):
            for k, v in value.items():
                if isinstance(v, list) and v and isinstance(v[0], dict):
                    out += [(key, k, 0, a) for a in v[0]]
                else:
                    out.append((key, k))
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            out += [(key, 0, a) for a in value[0]]
        else:
            out.append((key,))
    return out


BASE = tomllib.loads(DESCRIPTION.read_text(encoding="utf-8"))
PLACES = _places(BASE)


def _check_specs(specs) -> None:
    """What read_description returned: finite, positive where a size is required."""
    assert specs
    for s in specs:
        for name in ("diameter", "wall_thickness", "mass_per_length", "duration",
                     "archive_step"):
            value = getattr(s, name)
            assert math.isfinite(value) and value > 0, (name, value)
        for support in s.supports:
            gap = support["gap_m"]
            assert math.isfinite(gap) and gap >= 0, support


def _forces_of(specs) -> None:
    """The first tube's modal forces: finite (or a fretwear error)."""
    out, _ = only_fretwear(tube_forces, specs[0])
    if out is not None:
        _, _, t, forces = out
        assert np.isfinite(t).all() and np.isfinite(forces).all()


@deterministic(40)
@given(data=mutated(DESCRIPTION.read_bytes()))
def test_a_mutated_description_reads_or_says_why(data):
    specs, _ = only_fretwear(read_description, _file(data))
    if specs is not None:
        _check_specs(specs)


@deterministic(60)
@given(place=st.sampled_from(PLACES), value=ODD, build=st.booleans())
def test_an_odd_description_value_reads_or_says_why(place, value, build):
    import copy

    raw = copy.deepcopy(BASE)
    target = raw
    for step in place[:-1]:
        target = target[step]
    target[place[-1]] = value
    # a short simulation: the forces are built for the changed key, not for 0.7 s of flow
    if place[:2] != ("simulation", "duration_s"):
        raw["simulation"]["duration_s"] = 0.05
    specs, _ = only_fretwear(read_description, _file(_write(raw)))
    if specs is None:
        return
    _check_specs(specs)
    if build:
        _forces_of(specs)


FLOATS = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                   st.sampled_from([0.0, -0.0, 1e-300, 1e300, 5e-324, 1e-4, 1.0]),
                   st.text(max_size=3), st.integers(-10**30, 10**30), st.none(),
                   st.lists(st.floats(), max_size=2))
DEPTHS = st.one_of(FLOATS, st.lists(st.floats(allow_nan=True, allow_infinity=True),
                                    min_size=0, max_size=4))


def _finite_where_inputs_are(result, *inputs) -> None:
    values = np.asarray(result, dtype=float)
    given = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in inputs))
    finite = np.logical_and.reduce([np.isfinite(g) for g in given]) if given else True
    assert np.isfinite(values[finite]).all() if values.shape else \
        (np.isfinite(values) or not np.all(finite)), (result, inputs)


@deterministic(80)
@given(a=FLOATS, b=FLOATS, sigma=FLOATS, measured=DEPTHS, true=DEPTHS)
def test_a_sizing_model_of_odd_values(a, b, sigma, measured, true):
    model, _ = only_fretwear(SizingModel, intercept=a, slope=b, sigma=sigma)
    if model is None:
        return
    for call, args in ((model.true_depth, (measured,)), (model.likelihood, (measured, true))):
        try:
            arrays = [np.asarray(x, dtype=float) for x in args]
            np.broadcast_shapes(*(x.shape for x in arrays))
        except (TypeError, ValueError):
            continue   # not numbers: numpy's own error before fretwear's code runs
        result, _ = only_fretwear(call, *args)
        if result is not None:
            _finite_where_inputs_are(result, *args)
    assert math.isfinite(model.true_depth_sigma())


@deterministic(80)
@given(first=FLOATS, second=FLOATS, log=st.booleans(), from_depths=st.booleans(),
       depth=DEPTHS, level=FLOATS)
def test_a_pod_of_odd_values(first, second, log, from_depths, depth, level):
    if from_depths:
        pod, _ = only_fretwear(LogisticPOD.from_depths, first, second, log_depth=log)
    else:
        pod, _ = only_fretwear(LogisticPOD, beta0=first, beta1=second, log_depth=log)
    if pod is None:
        return
    try:
        arr = np.asarray(depth, dtype=float)
    except (TypeError, ValueError):
        arr = None
    if arr is not None:
        for call in (pod, pod.miss):
            result, _ = only_fretwear(call, arr)
            values = np.asarray(result, dtype=float)
            # a probability in [0, 1] wherever the depth is a number (log model: d <= 0 has
            # POD 0); NaN only from a NaN depth
            ok = ~np.isnan(arr)
            assert ((values[ok] >= 0) & (values[ok] <= 1)).all(), (pod, depth, result)
    at, _ = only_fretwear(pod.depth_at, level)
    if at is not None:
        assert not math.isnan(at), (pod, level, at)


@deterministic(60)
@given(p=st.one_of(st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=5),
                   st.lists(st.lists(st.floats(0, 1), min_size=2, max_size=2), max_size=4),
                   st.lists(st.sampled_from([0.0, 1.0, 5e-324, 1 - 1e-16]), max_size=5)),
       tubes=st.lists(st.one_of(st.integers(0, 3), st.text(max_size=2)), max_size=5),
       weights=st.one_of(st.none(), st.lists(st.floats(allow_nan=True), max_size=3)),
       target=FLOATS)
def test_a_bundle_risk_of_odd_values(p, tubes, weights, target):
    risk, _ = only_fretwear(bundle_risk, p, tubes, weights)
    if risk is None:
        return
    any_, _ = only_fretwear(risk.probability_any)
    assert any_ is None or 0.0 <= any_ <= 1.0, (p, tubes, weights, any_)
    plugged, _ = only_fretwear(plugging_list, risk, target)
    if plugged is not None:
        assert set(plugged) <= set(risk.tubes.tolist())
    sample, _ = only_fretwear(inspection_sample, risk, target)
    if sample is not None:
        assert set(sample) <= set(risk.tubes.tolist())
