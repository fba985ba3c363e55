"""Atomic output: write to a temporary file beside the target, then rename over it."""

from __future__ import annotations

import contextlib
import glob
import os
import shutil
import stat
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import IO

from fretwear.errors import FretwearError, InputError


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, *, sweep: bool = True) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success it replaces ``path`` atomically.

    On error the temporary file is removed and ``path`` is left as it was. Parent directories
    are created. The new file gets the permissions of the one it replaces, or those of an
    ordinary ``open()`` (0666 less the umask). With ``sweep`` (the default), the temporaries
    of ``path`` that a killed run left (older than :data:`STALE_SECONDS`) are removed after
    the write: a listing of the folder. A writer of many files of names never written twice
    (a bundle's parts) passes False and sweeps the folder once itself
    (:func:`remove_stale_in`): a listing per write made 2 000 writes cost 1.6 -> 3.1 ms each.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_path(d / "out.txt") as tmp:
    ...     _ = tmp.write_text("ok")
    >>> (d / "out.txt").read_text()
    'ok'
    """
    target = Path(path)
    if target.is_dir():
        raise InputError(f"output {str(target)!r} is a directory; give a file name")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp_name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp",
                                        dir=target.parent)
    except OSError as exc:
        raise _cannot_write(target, exc) from exc
    os.close(fd)
    tmp = Path(tmp_name)
    try:
        # mkstemp creates 0600: give the output the mode an ordinary open() would (or keep the
        # mode of the file it replaces).
        os.chmod(tmp, _output_mode(target))
        yield tmp
        os.replace(tmp, target)
        if sweep:
            _remove_stale(target, ".tmp")
    except BaseException as exc:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
        if isinstance(exc, OSError):  # the user's path in the message, never the temporary one
            raise _cannot_write(target, exc, tmp) from exc
        if isinstance(exc, FretwearError) and str(tmp) in str(exc):
            raise type(exc)(str(exc).replace(str(tmp), str(target))) from exc
        raise


def _cannot_write(target: Path, exc: OSError, tmp: Path | None = None) -> InputError:
    """An :class:`InputError` naming the user's output path (not the temporary file)."""
    reason = exc.strerror or str(exc)
    if tmp is not None:
        reason = reason.replace(str(tmp), str(target)).replace(tmp.name, target.name)
    return InputError(f"cannot write the output {str(target)!r}: {reason}; check that its "
                      "folder exists and is writable and that the disk is not full")


#: Age [s] after which a temporary file or folder of an output, left by a killed run, is removed
#: by the next successful write of that output.
STALE_SECONDS = 60.0


def _remove_stale(target: Path, *suffixes: str) -> None:
    """Remove the temporary files/folders of ``target`` that killed runs left behind
    (``.<name>.<random><suffix>``, untouched for :data:`STALE_SECONDS`)."""
    for suffix in suffixes:
        remove_stale_in(target.parent, f"{glob.escape(target.name)}.*{suffix}")


def remove_stale_in(folder: str | os.PathLike, pattern: str) -> int:
    """Remove the temporaries ``.<pattern>`` in ``folder`` (a glob pattern after the leading
    dot, e.g. ``"part-*.tmp"``) untouched for :data:`STALE_SECONDS` [s]: what runs killed
    while writing left. Returns how many were removed.

    Examples
    --------
    >>> import os, tempfile, pathlib, time
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> old, new = d / ".part-1.parquet.x1.tmp", d / ".part-2.parquet.x2.tmp"
    >>> _ = old.write_text("half"), new.write_text("busy")
    >>> os.utime(old, (time.time() - 2 * STALE_SECONDS,) * 2)
    >>> remove_stale_in(d, "part-*.tmp"), sorted(p.name for p in d.iterdir())
    (1, ['.part-2.parquet.x2.tmp'])
    """
    limit = time.time() - STALE_SECONDS
    removed = 0
    for leftover in Path(folder).glob(f".{pattern}"):
        try:
            if leftover.lstat().st_mtime >= limit:
                continue
            if leftover.is_dir() and not leftover.is_symlink():
                shutil.rmtree(leftover, ignore_errors=True)
            else:
                leftover.unlink()
            removed += 1
        except OSError:
            continue
    return removed


def _output_mode(target: Path) -> int:
    try:
        return stat.S_IMODE(target.stat().st_mode)
    except FileNotFoundError:
        mask = os.umask(0)
        os.umask(mask)
        return 0o666 & ~mask


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike, mode: str = "w", *, sweep: bool = True,
                 **open_kwargs) -> Iterator[IO]:
    """Open a temporary file for writing; it replaces ``path`` atomically when closed cleanly
    (``sweep``: as :func:`atomic_path`)."""
    with atomic_path(path, sweep=sweep) as tmp, open(tmp, mode, **open_kwargs) as handle:
        yield handle


def _same_file(a: Path, b: Path) -> bool:
    try:
        if a.exists() and b.exists():
            return os.path.samefile(a, b)  # hard links and symbolic links too
    except OSError:
        pass
    return os.path.normcase(os.path.abspath(a)) == os.path.normcase(os.path.abspath(b))


def check_outputs(outputs, inputs, *, force: bool = False, overwritable=()) -> None:
    """Refuse an output that would overwrite one of the inputs (nothing the user gave is lost).

    Parameters
    ----------
    outputs : mapping
        ``{what: path or None}`` of the files about to be written (``"-o"``, ``"--report"``).
    inputs : mapping
        ``{what: path or None}`` of the files read (history, restart table, database, obstacle
        table, case file).
    force : bool
        Allow overwriting the inputs named in ``overwritable`` (``--force``).
    overwritable : collection of str
        Inputs that ``force`` lets an output replace (a restart table continued in place).

    Raises
    ------
    InputError
        Naming the output, the input it would replace, and the fix.

    Examples
    --------
    >>> check_outputs({"-o": "a.csv"}, {"history file": "b.csv"})
    >>> try:
    ...     check_outputs({"-o": "./a.csv"}, {"history file": "a.csv"})
    ... except InputError as exc:
    ...     print(str(exc)[:60])
    output -o './a.csv' is the history file 'a.csv': writing it
    """
    for what, out in outputs.items():
        if out is None:
            continue
        for source, given in inputs.items():
            if given is None or not _same_file(Path(out), Path(given)):
                continue
            if force and source in overwritable:
                continue
            hint = (" (add --force to replace it with the continued table)"
                    if source in overwritable else "")
            raise InputError(f"output {what} {str(out)!r} is the {source} {str(given)!r}: "
                             f"writing it would destroy an input; choose another output "
                             f"path{hint}")


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux renameat2 RENAME_EXCHANGE); False when unavailable."""
    try:
        import ctypes
        import ctypes.util

        libc = ctypes.CDLL(ctypes.util.find_library("c") or None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    done = renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange)
    return done == 0


@contextlib.contextmanager
def atomic_folder(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary folder beside ``path``; on success it replaces ``path`` as a whole.

    A reader (or a run killed at any instant) sees the old folder or the complete new one,
    never a mix: the new folder is written under a hidden temporary name, then exchanged with
    the old one in one step (Linux ``renameat2(RENAME_EXCHANGE)``; elsewhere the old folder is
    moved aside first, a window of two renames) and the old one is deleted. On error the
    temporary folder is deleted and ``path`` is left as it was.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_folder(d / "cycle_01") as tmp:
    ...     _ = (tmp / "table.csv").write_text("new")
    >>> sorted(p.name for p in d.iterdir()), (d / "cycle_01" / "table.csv").read_text()
    (['cycle_01'], 'new')
    """
    target = Path(path)
    if target.exists() and not target.is_dir():
        raise InputError(f"output folder {str(target)!r} is a file; give a folder name")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent))
    except OSError as exc:
        raise _cannot_write(target, exc) from exc
    try:
        yield tmp
        if not target.exists():
            os.rename(tmp, target)
        elif _exchange(tmp, target):  # tmp now holds the old folder
            shutil.rmtree(tmp, ignore_errors=True)
        else:
            old = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".old",
                                        dir=target.parent))
            os.rename(target, old / target.name)
            os.rename(tmp, target)
            shutil.rmtree(old, ignore_errors=True)
        _remove_stale(target, ".tmp", ".old")
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
