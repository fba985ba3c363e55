"""A bundle interrupted while its waves are built or while its end runs (the summary made in a
thread beside the rest), and that thread failing: the interrupt is a BundleInterrupted, the
error reaches the caller, and a rerun finishes from what was written (review of issue 28's
afternoon round; the end before it closed the summary's rows itself)."""

from __future__ import annotations

import pytest
from bundle_helpers import oscillator, write_bundle

from fretwear.bundle import engine, outputs, run_bundle
from fretwear.bundle import result as result_module
from fretwear.bundle.interrupted import BundleInterrupted

pytest.importorskip("pyarrow")


def test_ctrl_c_in_the_second_wave_is_a_bundle_interrupt(tmp_path, monkeypatch):
    manifest, case = write_bundle(tmp_path, oscillator(), 4)
    monkeypatch.setattr(engine, "FIRST_WAVE", 2)
    real = engine._build_tasks
    calls = []

    def build(*args, **kwargs):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(engine, "_build_tasks", build)
    with pytest.raises(BundleInterrupted):
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    monkeypatch.setattr(engine, "_build_tasks", real)
    again = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    assert again.stats["done"] + again.stats["skipped"] == 4


def test_ctrl_c_at_the_end_while_the_summary_thread_runs(tmp_path, monkeypatch):
    manifest, case = write_bundle(tmp_path, oscillator(), 4)
    real = outputs._news

    def news(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(outputs, "_news", news)
    with pytest.raises(BundleInterrupted):
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    monkeypatch.setattr(outputs, "_news", real)
    again = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    assert again.stats["skipped"] == 4


def test_an_error_in_the_summary_thread_reaches_the_caller(tmp_path, monkeypatch):
    manifest, case = write_bundle(tmp_path, oscillator(), 4)

    def broken(rows, contacts, limit):
        rows.close()
        raise RuntimeError("summary broke")

    monkeypatch.setattr(outputs, "summarize_ahead", broken)
    with pytest.raises(RuntimeError, match="summary broke"):
        run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    monkeypatch.undo()
    again = run_bundle(manifest, case, scheduler="serial", output=tmp_path / "out")
    assert again.stats["skipped"] == 4
    assert list(again.summary()["contact"]) == list(
        result_module.summarize(again.table, again.contacts, limit=None, limit_m=None,
                                wall_thickness=None)["contact"])
