"""The channels of a file's columns (mapping, units, factors to SI) are remembered for the last
column layouts read without ``columns`` or ``units`` options (``io.sources._LAYOUTS``: a
bundle's files share one). Each file is compared with the uncached resolution of its own
columns (:func:`fretwear.io.channels.resolve_columns` and ``resolve_units``, the reference) and
with the values in SI its raw numbers give by the units' definitions (1 ms = 1e-3 s, 1 mm =
1e-3 m, 1 kN = 1e3 N), after files of other layouts were read in between."""

from __future__ import annotations

from collections import OrderedDict

import numpy as np
import pytest

from fretwear.errors import FormatError
from fretwear.io import read_history, sources
from fretwear.io.channels import resolve_columns, resolve_units

pytestmark = pytest.mark.filterwarnings("ignore::fretwear.errors.UnitsWarning")  # 1 s steps

RAW = np.array([[0.0, 1.0, 2.0], [1.0, 2.0, 3.0], [0.5, 0.25, 0.125], [0.0, 0.0, 0.0]])


def _csv(path, header):
    rows = "".join(",".join(f"{v:g}" for v in RAW[:, k]) + "\n" for k in range(3))
    path.write_text(",".join(header) + "\n" + rows)
    return path


def _prepared(path):
    source, mapping, factors, _, metadata = sources._prepare(path, None, None, None, None, {})
    return source, mapping, factors, metadata


def test_every_layout_gets_its_own_channels(tmp_path, monkeypatch):
    monkeypatch.setattr(sources, "_LAYOUTS", OrderedDict())
    files = {
        "si": (_csv(tmp_path / "si.csv", ["time", "fn", "vt1", "vt2"]), (1.0, 1.0, 1.0)),
        "mm": (_csv(tmp_path / "mm.csv", ["t [ms]", "fn [kN]", "vt1 [mm/s]", "vt2 [mm/s]"]),
               (1e-3, 1e3, 1e-3)),
        "inst": (_csv(tmp_path / "inst.csv", ["INST", "FN", "VT1", "VT2"]), (1.0, 1.0, 1.0)),
        "si2": (_csv(tmp_path / "si2.csv", ["time", "fn", "vt1", "vt2"]), (1.0, 1.0, 1.0)),
    }
    order = list(files) + list(files)[::-1]
    for name in order:
        path, (kt, kf, kv) = files[name]
        source, mapping, factors, metadata = _prepared(path)
        expected = resolve_columns(source.columns, None, label=source.label)
        unit_of, expected_factors = resolve_units(expected, source.units, None,
                                                  label=source.label)
        assert mapping == expected, name
        assert factors == expected_factors and metadata["units"] == unit_of, name
        assert metadata["columns"] == {ch: source.columns[p] for ch, p in expected.items()}
        # a caller's change to what it was given never reaches the next file
        mapping.clear()
        factors["time"] = 99.0
        metadata["units"]["time"] = "changed"
        h = read_history(path)
        assert np.allclose(h.time, kt * RAW[0], rtol=1e-15, atol=0)
        assert np.allclose(h.normal_force, kf * RAW[1], rtol=1e-15, atol=0)
        assert np.allclose(h.vt1, kv * RAW[2], rtol=1e-15, atol=0)
    assert len(sources._LAYOUTS) == 3  # si.csv and si2.csv share their layout


def test_options_are_resolved_at_every_read_and_errors_raised_again(tmp_path, monkeypatch):
    monkeypatch.setattr(sources, "_LAYOUTS", OrderedDict())
    path = _csv(tmp_path / "si.csv", ["time", "fn", "vt1", "vt2"])
    h = read_history(path, units={"time": "ms"})
    assert np.allclose(h.time, 1e-3 * RAW[0], rtol=1e-15, atol=0)
    assert not sources._LAYOUTS  # an option: not remembered
    bad = _csv(tmp_path / "bad.csv", ["time", "fn", "speed", "vt2"])
    for _ in range(2):
        with pytest.raises(FormatError, match="required channel"):
            read_history(bad)
    assert not sources._LAYOUTS
