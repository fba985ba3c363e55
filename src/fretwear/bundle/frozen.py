"""The client's garbage collector during a bundle run (issue 28): the objects alive at the
run's start frozen, and those surviving each pass of the older generations frozen too
(:func:`gc_frozen`); the collector off while the run's end assembles its result
(:func:`collector_paused`)."""

from __future__ import annotations

import contextlib
import gc


@contextlib.contextmanager
def gc_frozen():
    """Run a block with the objects alive at its start frozen (:func:`gc.freeze`): the garbage
    collector's full passes during the block go over the objects made since, not over every
    object of the process (pandas, Dask, numba: some 150 000, a full pass 0.08 s on an idle
    core, 0.1-0.24 s beside two busy workers, one run of 500 contacts in three). Nothing is
    frozen when the collector is disabled or the process froze objects before the run (their
    freeze is left as it is); unfrozen at the end, a cycle among the old objects is collected
    then. Python unfreezes all or nothing: objects another thread of the process freezes while
    the run goes on (or a concurrent run_bundle's) are unfrozen with them, which costs that
    thread the speed of its freeze, never a result.

    What survives a pass of generation 1 or 2 during the block is frozen too
    (:func:`freeze_survivors`):
    the records and tasks the client holds grow with the contacts, and each full pass went over
    all of them again (issue 28: 0.6 s of the client's CPU at 3x10^4 contacts)."""
    if not gc.isenabled() or gc.get_freeze_count():
        yield
        return
    gc.freeze()
    gc.callbacks.append(freeze_survivors)
    try:
        yield
    finally:
        with contextlib.suppress(ValueError):
            gc.callbacks.remove(freeze_survivors)
        gc.unfreeze()


def freeze_survivors(phase: str, info: dict) -> None:
    """A :data:`gc.callbacks` callback: at the end of a pass of generation 1 or 2, every object
    the collector tracks is frozen (:func:`gc.freeze`: those the pass kept, and any made since
    by another thread, Dask's event loop), so that the next passes go over the objects made
    since: the records, tasks and parts the client keeps till the end survive their first
    passes, and were walked again by every full pass (issue 28: 25 full passes, 0.7 s of the
    client's CPU at 10^5 contacts; frozen after the middle generation's passes too, no full
    pass is left and the client's peak memory was 1.26 GB against 1.32). An object frozen then
    and found in a garbage cycle later (freed by its reference count otherwise, frozen or not)
    is collected once the run unfreezes, its memory held until then."""
    if phase == "stop" and info.get("generation", 0) >= 1:
        gc.freeze()


@contextlib.contextmanager
def collector_paused():
    """Python's cyclic garbage collector off in the block (back on after, where it was)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()
