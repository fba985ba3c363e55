"""Optional dependencies (fretwear._optional): each entry point that needs one, with the package
made unimportable (``sys.modules[name] = None``, what Python does for a missing package), raises
MissingDependencyError naming the extra to install, never a bare ModuleNotFoundError; the code
that does not need it still runs (the dynamics without pyarrow, the power without numba)."""

from __future__ import annotations

import ast
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

from fretwear import _optional
from fretwear.cli import main
from fretwear.dynamics import ModalModel, Shock, simulate
from fretwear.errors import FretwearError, MissingDependencyError
from fretwear.history import ContactHistory
from fretwear.io import read_history, write_history
from fretwear.workflows.loop import iterate_case

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def _hide(monkeypatch, *modules: str) -> None:
    for name in modules:
        monkeypatch.setitem(sys.modules, name, None)


def _history(n: int = 50) -> ContactHistory:
    t = np.linspace(0.0, 1.0, n)
    return ContactHistory(time=t, normal_force=1.0 + t, vt1=0.1 * np.cos(t),
                          vt2=0.1 * np.sin(t), dy=1e-4 * np.cos(t), dz=1e-4 * np.sin(t))


# ------------------------------------------------------------------------ require / optional
@pytest.mark.parametrize("module", sorted(_optional.EXTRAS))
def test_require_names_the_extra_of_every_optional_module(module, monkeypatch):
    _hide(monkeypatch, module)
    with pytest.raises(MissingDependencyError) as info:
        _optional.require(module, purpose="this test")
    extra = _optional.EXTRAS[module]
    assert str(info.value) == (f"this test needs the optional package {module!r}: "
                               f"pip install 'fretwear[{extra}]'")
    assert isinstance(info.value, ImportError) and isinstance(info.value, FretwearError)
    assert _optional.optional(module) is None


def test_a_broken_install_is_not_reported_as_missing(monkeypatch, tmp_path):
    """An ImportError from inside the package (not its absence) says so and keeps the cause."""
    (tmp_path / "zarr").mkdir()
    (tmp_path / "zarr" / "__init__.py").write_text("import a_module_that_does_not_exist_xyz\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "zarr", raising=False)
    with pytest.raises(MissingDependencyError, match=r"installed but cannot be imported "
                                                     r"\(ModuleNotFoundError: .*xyz"):
        _optional.optional("zarr")
    monkeypatch.delitem(sys.modules, "zarr", raising=False)


def test_an_unknown_module_is_a_programming_error():
    with pytest.raises(KeyError, match="not an optional dependency of fretwear"):
        _optional.require("requests")


def _optional_uses() -> dict[str, list[str]]:
    """module -> places in src/fretwear that require() or optional() it (string literals)."""
    uses: dict[str, list[str]] = {}
    for path in sorted((ROOT / "src" / "fretwear").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        names = {alias.asname or alias.name for node in ast.walk(tree)
                 if isinstance(node, ast.ImportFrom) and node.module == "fretwear._optional"
                 for alias in node.names if alias.name in ("require", "optional")}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                    and node.func.id in names and node.args
                    and isinstance(node.args[0], ast.Constant)
                    and isinstance(node.args[0].value, str)):
                uses.setdefault(node.args[0].value, []).append(
                    f"{path.relative_to(ROOT)}:{node.lineno}")
    return uses


def _provides(requirement: str) -> set[str]:
    """Top-level modules a requirement string installs (``dask[distributed]`` -> dask and
    distributed), lower case."""
    name, _, rest = re.match(r"([A-Za-z0-9_.\-]+)(\[[^\]]*\])?", requirement).group(1, 1, 2)
    out = {name.lower().replace("-", "_")}
    extras = re.match(r"[A-Za-z0-9_.\-]+\[([^\]]*)\]", requirement)
    if extras and name.lower() == "dask" and "distributed" in extras.group(1):
        out.add("distributed")
    return out


def test_every_optional_module_in_use_is_in_its_extra_of_pyproject():
    """Each module the code requires is installed by the extra the error message names."""
    extras = PYPROJECT["project"]["optional-dependencies"]
    uses = _optional_uses()
    assert uses, "no require()/optional() call found: the scan is broken"
    for module, places in uses.items():
        top = module.partition(".")[0]
        extra = _optional.EXTRAS.get(top)
        assert extra is not None, f"{places}: {top} is not in fretwear._optional.EXTRAS"
        assert extra in extras, (f"{places}: {top} needs the extra [{extra}], which "
                                 "pyproject.toml does not declare")
        provided = set().union(*(_provides(r) for r in extras[extra]))
        assert top.lower() in provided, f"pyproject's [{extra}] does not install {top}"


# ------------------------------------------------------------------------ formats: [formats]
@pytest.mark.parametrize("suffix, module", [(".parquet", "pyarrow"), (".h5", "h5py"),
                                            (".nc", "netCDF4")])
def test_binary_formats_name_the_formats_extra(suffix, module, tmp_path, monkeypatch):
    path = write_history(_history(), tmp_path / f"h{suffix}")
    _hide(monkeypatch, module, f"{module}.parquet")
    with pytest.raises(MissingDependencyError, match=r"pip install 'fretwear\[formats\]'"):
        read_history(path)
    with pytest.raises(MissingDependencyError, match=r"pip install 'fretwear\[formats\]'"):
        write_history(_history(), tmp_path / f"new{suffix}")
    assert not (tmp_path / f"new{suffix}").exists()


# _history() is sampled every 20 ms: as a file its step is flagged (likely ms), irrelevant here
@pytest.mark.filterwarnings("ignore:.*median sampling step:fretwear.errors.UnitsWarning")
def test_csv_without_pyarrow_uses_pandas(tmp_path, monkeypatch):
    _hide(monkeypatch, "pyarrow", "pyarrow.csv")
    back = read_history(write_history(_history(), tmp_path / "h.csv"))
    np.testing.assert_array_equal(back.normal_force, _history().normal_force)


# ---------------------------------------------------------- dynamics: pyarrow only to stream
def _model():
    return ModalModel(frequencies=[5.0], damping_ratios=0.02, masses=1.0,
                      shock_shapes=[[[1.0], [0.0]]])


def test_dynamics_runs_without_pyarrow_and_needs_it_only_to_stream(tmp_path, monkeypatch):
    shock = Shock(point=0, obstacle="circle", gap=1.0, normal_stiffness=1e3)
    kw = dict(duration=0.05, time_step=1e-4, initial_displacement=[1e-3])
    _hide(monkeypatch, "pyarrow", "pyarrow.parquet")
    in_memory = simulate(_model(), [shock], **kw)
    assert in_memory.history(0).time.size > 10
    with pytest.raises(MissingDependencyError,
                       match=r"streaming the dynamics to Parquet \(output_dir\) needs the "
                             r"optional package 'pyarrow': pip install 'fretwear\[formats\]'"):
        simulate(_model(), [shock], output_dir=tmp_path / "h", **kw)


@pytest.mark.parametrize("hidden, extra", [(("pyarrow", "pyarrow.parquet"), "formats"),
                                           (("matplotlib.pyplot",), "plot")])
def test_loop_says_which_extra_before_computing(hidden, extra, tmp_path, monkeypatch):
    import fretwear.workflows.loop as loop

    def no_dynamics(*args, **kwargs):
        raise AssertionError("the dynamics ran before the dependency check")

    monkeypatch.setattr(loop, "simulate", no_dynamics)
    _hide(monkeypatch, *hidden)
    with pytest.raises(MissingDependencyError, match=rf"pip install 'fretwear\[{extra}\]'"):
        iterate_case(ROOT / "examples" / "iterate_tube_support.toml", output=tmp_path,
                     plot=True)
    assert not any(tmp_path.iterdir())


# ------------------------------------------------------------------------ CLI: [plot]
def test_cli_plot_without_matplotlib_exits_2_naming_the_extra(tmp_path, monkeypatch, capsys):
    _hide(monkeypatch, "matplotlib.pyplot")
    code = main(["run", str(ROOT / "examples" / "tube_bav.toml"), "-q",
                 "--plot", str(tmp_path / "fig")])
    assert code == 2
    assert ("fretwear: error: --plot needs the optional package 'matplotlib.pyplot': "
            "pip install 'fretwear[plot]'") in capsys.readouterr().err
    assert not (tmp_path / "fig").exists()


# ------------------------------------------------------------------------ numba: [fast], fallback
def test_power_without_numba_falls_back_to_numpy():
    """In a fresh interpreter without numba: no error, the numpy kernel, the same power as the
    trapezoid rule of theory §2 computed here."""
    code = """
import sys
sys.modules["numba"] = None
import numpy as np
from fretwear.history import ContactHistory
from fretwear.power import wear_power
from fretwear.power.kernels import HAVE_NUMBA, fused, fused_numpy
from fretwear._numba import HAVE_NUMBA as H2
t = np.linspace(0.0, 2.0, 401)
fn, v = 1.0 + t, 0.1 + 0.0 * t
p = wear_power(ContactHistory(time=t, normal_force=fn, vt1=v, vt2=0 * t)).total
trapz = float(np.sum(0.5 * (fn[1:] * v[1:] + fn[:-1] * v[:-1]) * np.diff(t)) / 2.0)
print(HAVE_NUMBA, H2, fused("auto") is fused_numpy, abs(p - trapz) <= 1e-12 * trapz)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT)
    assert out.stdout.split() == ["False", "False", "True", "True"]


def test_a_kernel_whose_cache_cannot_be_written_is_compiled_without_it(monkeypatch):
    """numba refuses ``cache=True`` at decoration when it finds no folder to write the cache in
    (RuntimeError "cannot cache function ... no locator available"): fretwear._numba.njit then
    compiles without the disk cache; any other error of numba still raises."""
    from fretwear import _numba

    if not _numba.HAVE_NUMBA:
        pytest.skip("numba is not installed")
    asked = []

    class Refusing:
        @staticmethod
        def njit(*args, **kwargs):
            asked.append(dict(kwargs))
            if kwargs.get("cache"):
                raise RuntimeError("cannot cache function 'f': no locator available for file "
                                   "'/site-packages/fretwear/io/_compiled.py'")
            return lambda func: ("compiled", func)

    monkeypatch.setattr(_numba, "_numba", Refusing)

    def f(x):
        return x

    assert _numba.njit(cache=True, nogil=True)(f) == ("compiled", f)
    assert asked == [{"cache": True, "nogil": True}, {"cache": False, "nogil": True}]
    assert _numba.njit(nogil=True)(f) == ("compiled", f)  # no cache asked: numba's own njit

    class Broken:
        @staticmethod
        def njit(*args, **kwargs):
            raise RuntimeError("some other failure")

    monkeypatch.setattr(_numba, "_numba", Broken)
    with pytest.raises(RuntimeError, match="some other failure"):
        _numba.njit(cache=True)(f)


def test_reading_and_the_power_as_a_user_with_no_writable_cache_folder():
    """For real: a user (nobody) who can write neither the package's __pycache__ nor a home
    reads a long history (the compiled plausibility pass) and computes its power (KWU-EPRI's
    compiled class pass); numba would refuse to cache those kernels. Needs root (to become
    nobody) and setpriv; skipped where nobody cannot run this interpreter on this tree."""
    import shutil

    if os.name != "posix" or os.geteuid() != 0 or shutil.which("setpriv") is None:
        pytest.skip("needs root and setpriv to run as another user")
    as_nobody = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
    env = {**os.environ, "HOME": "/nonexistent", "PYTHONDONTWRITEBYTECODE": "1"}
    env.pop("NUMBA_CACHE_DIR", None)
    probe = subprocess.run([*as_nobody, sys.executable, "-c", "import numpy, fretwear.errors"],
                           capture_output=True, text=True, cwd="/", env=env)
    if probe.returncode != 0:
        pytest.skip(f"nobody cannot import fretwear from this tree: {probe.stderr[-200:]}")
    import tempfile

    folder = Path(tempfile.mkdtemp(prefix="fretwear-nobody-"))  # pytest's is root's only
    folder.chmod(0o755)
    csv = folder / "long.csv"
    t = np.arange(20_000) * 1e-5
    np.savetxt(csv, np.column_stack([t, 1.0 + np.sin(t * 900.0), 0.1 + 0 * t, 0 * t]),
               delimiter=",", header="time,normal_force,vt1,vt2", comments="")
    csv.chmod(0o644)
    code = f"""
from fretwear.io import read_history
from fretwear.power import wear_power
h = read_history({str(csv)!r})
print(len(h), wear_power(h, kwu=(None, None)).total > 0)
"""
    try:
        out = subprocess.run([*as_nobody, sys.executable, "-c", code], capture_output=True,
                             text=True, cwd="/", env=env)
    finally:
        shutil.rmtree(folder)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["20000", "True"]


def test_plausibility_of_a_long_history_without_numba():
    """In a fresh interpreter without numba, a history long enough for the compiled pass
    (io/_compiled.py) is checked by the numpy expressions: the speed in mm/s is caught with
    the largest ‖Vt‖ of numpy.hypot, and numba stays unimported."""
    code = """
import sys, warnings
sys.modules["numba"] = None
import numpy as np
from fretwear.history import ContactHistory
from fretwear.io import plausibility
n = 2 * plausibility._KERNEL_SAMPLES
t = np.arange(n) * 1e-5
v = 30.0 * np.sin(t * 700.0)
h = ContactHistory(time=t, normal_force=np.abs(np.sin(t * 300.0)), vt1=v, vt2=0.5 * v)
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    found = plausibility.check_plausibility(h)
top = float(np.hypot(h.vt1, h.vt2).max())
print(len(found), f"{top:.4g} m/s" in found[0], plausibility._compiled() is None)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT)
    assert out.stdout.split() == ["1", "True", "True"]


def test_every_module_imports_without_any_optional_package():
    """Optional packages are never imported at a module's top: with all of them unimportable, a
    fresh interpreter imports every module of fretwear."""
    code = f"""
import importlib, pathlib, sys, warnings
for name in {sorted(_optional.EXTRAS)!r}:
    sys.modules[name] = None
root = pathlib.Path({str(ROOT / "src" / "fretwear")!r})
failed = []
for path in sorted(root.rglob("*.py")):
    parts = path.relative_to(root.parent).with_suffix("").parts
    name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
    if name.endswith("conftest"):
        continue
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # the shims warn
        try:
            importlib.import_module(name)
        except Exception as exc:
            failed.append(f"{{name}}: {{type(exc).__name__}}: {{exc}}")
print("\\n".join(failed) or "ok")
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT)
    assert out.stdout.strip() == "ok", out.stdout
