"""Shared test set-up.

The CLI prints with rich, which wraps at the terminal width (80 columns when not a terminal, as
under CI). Tests that look for a phrase or a path in the printed summary must not depend on where
a temporary path happens to wrap, so every test sees a wide terminal.
"""

import faulthandler
import os
from pathlib import Path

import pytest

#: Test folders (and files) whose float results depend on the SIMD code path: marked
#: ``numeric`` and run a second time with SIMD turned down by ``tests/reduced_simd.py`` (part of
#: ``make test``), so that a test holding only on the processor that wrote it fails here.
NUMERIC = ("power", "table", "geometry", "obstacle", "dynamics", "laws", "flow", "assessment",
           "workflows/test_example_snapshots.py", "test_reduced_simd.py")


#: Hypothesis examples worth replaying on every run (found by deep runs), stored in the repo.
HYPOTHESIS_EXAMPLES = Path(__file__).resolve().parent / "hypothesis-examples"


#: A deep fuzz run (FRETWEAR_FUZZ_SCALE other than 1) explores; make test does not.
DEEP = os.environ.get("FRETWEAR_FUZZ_SCALE", "1").strip() not in ("", "1")


def _hypothesis_profile() -> None:
    """Property tests are deterministic in ``make test``: a fixed seed (0, set in
    :func:`pytest_configure`; the tests that ask for ``derandomize=True`` get a seed fixed by
    their source), hypothesis pinned in pyproject.toml, and the stored examples replayed
    read-only, so a run cannot fail by the luck of a draw. A deep run explores at random and
    stores what it finds in :data:`HYPOTHESIS_EXAMPLES`, to be made a fixed regression test
    (tests/fuzz/test_fuzz_regressions.py)."""
    try:
        from hypothesis import settings
        from hypothesis.database import DirectoryBasedExampleDatabase, ReadOnlyDatabase
    except ImportError:  # pragma: no cover - hypothesis is in the [dev] extra
        return
    stored = DirectoryBasedExampleDatabase(str(HYPOTHESIS_EXAMPLES))
    settings.register_profile("fretwear", database=ReadOnlyDatabase(stored), deadline=None,
                              print_blob=True)
    settings.register_profile("explore", database=stored, deadline=None, print_blob=True)
    settings.load_profile("explore" if DEEP else "fretwear")


_hypothesis_profile()


#: Seconds any one test may run in ``make test`` (the longest takes ~25 s on an idle 2-core
#: machine; ``FRETWEAR_TEST_WATCHDOG`` sets another); none in a deep fuzz run.
WATCHDOG = None if DEEP else float(os.environ.get("FRETWEAR_TEST_WATCHDOG", "600"))


#: A copy of the standard error made when pytest is configured: the watchdog's stacks written
#: there reach the terminal (fd 2 is pytest's capture file while a test runs, lost on exit).
_STDERR = None


@pytest.fixture(autouse=True)
def watchdog():
    """A test that hangs ends its process after :data:`WATCHDOG` seconds with every thread's
    stack on stderr (pytest-xdist then reports that test as failed, its worker crashed) instead
    of holding CI until its own time limit. Seen once in some hundreds of runs: the client of
    tests/bundle/test_bundle_dask.py's crashing-file test waiting on idle workers."""
    if WATCHDOG is None or _STDERR is None:
        yield
        return
    faulthandler.dump_traceback_later(WATCHDOG, exit=True, file=_STDERR)
    yield
    faulthandler.cancel_dump_traceback_later()


@pytest.hookimpl(tryfirst=True)
def pytest_configure(config):
    """The fixed seed of make test's property tests (``--hypothesis-seed`` still wins), and the
    watchdog's copy of the standard error."""
    global _STDERR
    if _STDERR is None:
        _STDERR = os.dup(2)
    if not DEEP and getattr(config.option, "hypothesis_seed", "absent") is None:
        config.option.hypothesis_seed = 0


def pytest_collection_modifyitems(config, items):
    root = Path(__file__).resolve().parent
    marked = [root / part for part in NUMERIC]
    for item in items:
        path = Path(str(item.path)).resolve()
        if any(path == m or m in path.parents for m in marked):
            item.add_marker(pytest.mark.numeric)


@pytest.fixture(autouse=True)
def _wide_terminal(monkeypatch):
    monkeypatch.setenv("COLUMNS", "240")


#: The [obstacle] section of the small control-rod case below (a bore, coarse steps: fast).
GRAPPE_OBSTACLE = """[obstacle]
type = "circle"
wall_thickness_m = 0.47e-3
step_deg = 5.0
resolution_deg = 1.0
"""


def write_grappe_case(path, history, *, instants: str = "[1000, 5000]", sectors: int = 4,
                      obstacle: bool = False, extra: str = "") -> Path:
    """A small case file: a control rod (304L) in a guide-card notch (GRAPPE_1_ENCO), Archard
    with both bodies wearing, ``history`` read from a file; with ``obstacle`` the
    :data:`GRAPPE_OBSTACLE` section; ``extra`` TOML appended."""
    path = Path(path)
    path.write_text(f"""[history]
file = "{history}"
[law]
name = "ARCHARD"
mobile = {{ COEF_USURE = 30e-15 }}
obstacle = {{ COEF_USURE = 17e-15 }}
[geometry]
contact_type = "GRAPPE_1_ENCO"
mobile_radius_m = 4.85e-3
obstacle_radius_m = 5.25e-3
obstacle_width_m = 20e-3
[sectors]
count = {sectors}
[time]
instants = {instants}
unit = "h"
{GRAPPE_OBSTACLE if obstacle else ""}{extra}""")
    return path


@pytest.fixture
def grappe_case():
    """:func:`write_grappe_case`, for tests in any folder."""
    return write_grappe_case


@pytest.fixture(scope="session")
def example_bundle_out(tmp_path_factory) -> Path:
    """The shipped examples/bundle run once (serial), its output directory (the assessment's
    campaign and coverage tests share it)."""
    import warnings

    from fretwear.bundle import run_bundle

    example = Path(__file__).resolve().parents[1] / "examples" / "bundle"
    out = tmp_path_factory.mktemp("example") / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run_bundle(example / "manifest.csv", example / "bundle.toml", scheduler="serial",
                   output=out)
    return out
