"""Reading files safely: every failure a file can cause becomes a fretwear error naming the file.

Three layers of protection, used by every reader of fretwear (histories, wear tables, databases,
case files, obstacle tables):

* :func:`readable_file` checks a path before it is opened (missing, a directory, a name too
  long, no read permission) and raises :class:`~fretwear.errors.InputError` naming the user's
  path and the fix.
* :func:`reading` is a context manager around the parsing of one file: the exceptions a
  damaged file makes the parsing libraries raise (truncated gzip ``EOFError`` and ``zlib.error``,
  ``zipfile.BadZipFile``, ``UnicodeDecodeError``, pandas' ``EmptyDataError``/``ParserError``,
  pyarrow's ``OSError``/``ArrowInvalid``, h5py's ``RuntimeError``/``KeyError``, netCDF4's errors,
  ``MemoryError`` from a corrupt size field ...) become a :class:`~fretwear.errors.FormatError`
  naming the file and its format; operating-system errors become an
  :class:`~fretwear.errors.InputError`.
* :func:`probe` checks an HDF5 or NetCDF file before the C library opens it in this process:
  the signature and the size it declares (a truncated file is refused), then its structure is
  walked by a child process (``sys.executable``) with a time limit (:data:`PROBE_TIMEOUT`), so
  a file that makes the C library crash (segmentation fault) or loop forever ends in a
  :class:`FormatError`, not in a dead or hung interpreter. The child is long-lived, one per
  process (a bundle's worker, a command): it walks every file it is sent, and only a crash or a
  hang costs a new one; a child per file cost 0.2 s a file (Python's start, h5py's import).
  The result is remembered per file (path, size, modification time).

Examples
--------
>>> import tempfile, pathlib
>>> p = pathlib.Path(tempfile.mkdtemp()) / "h.csv.gz"
>>> _ = p.write_bytes(b"\\x1f\\x8b\\x08\\x00" + b"\\x00" * 6 + b"\\x01")  # a truncated gzip
>>> import gzip
>>> try:
...     with reading(p, "csv"):
...         _ = gzip.open(p).read()
... except FormatError as exc:
...     print(str(exc).split(" (")[0])
... # doctest: +ELLIPSIS
/...h.csv.gz: damaged or truncated csv file
"""

from __future__ import annotations

import atexit
import contextlib
import errno
import json
import os
import queue
import signal
import stat
import struct
import subprocess
import sys
import threading
import warnings
import zipfile
import zlib
from pathlib import Path
from typing import Any

from fretwear.errors import FormatError, FretwearError, InputError, WholeReadWarning

__all__ = ["readable_file", "reading", "probe", "warn_whole_read", "PROBE_TIMEOUT",
           "BINARY_FORMATS", "WHOLE_READ_WARNING_BYTES"]

#: Seconds the child process may take to walk an HDF5/NetCDF file's structure before the file
#: is declared unreadable (a corrupt file can make the C library loop forever).
PROBE_TIMEOUT = 20.0
#: Formats parsed by C libraries (pyarrow, h5py, netCDF4, numpy's zip reader): any exception
#: they raise while reading is the file's fault.
BINARY_FORMATS = frozenset({"parquet", "hdf5", "netcdf", "npz"})

HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"
NETCDF_CLASSIC_MAGIC = (b"CDF\x01", b"CDF\x02", b"CDF\x05")

# exceptions that mean "the bytes of this file are damaged", whatever the format
_DAMAGED: tuple[type[BaseException], ...] = (
    EOFError, zlib.error, zipfile.BadZipFile, UnicodeError, struct.error, MemoryError,
    OverflowError, NotImplementedError)
# and, for formats parsed by C libraries, whatever they raise
_LIBRARY: tuple[type[BaseException], ...] = (
    ValueError, TypeError, KeyError, IndexError, RuntimeError, AttributeError)


def _pandas_errors() -> tuple[type[BaseException], ...]:
    pandas = sys.modules.get("pandas")  # not imported: no pandas code ran, none of its errors
    if pandas is None:
        return ()
    return (pandas.errors.EmptyDataError, pandas.errors.ParserError)


def _os_problem(exc: OSError) -> str | None:
    """A plain-words reason for an operating-system error, or None when it is not one."""
    reasons = {errno.ENOENT: "does not exist", errno.EACCES: "cannot be read (permission "
               "denied): check its permissions", errno.EPERM: "cannot be read (operation not "
               "permitted)", errno.EISDIR: "is a directory, not a file", errno.ENOTDIR:
               "has a parent that is not a directory", errno.ENAMETOOLONG: "has a name too "
               "long for the file system", errno.ELOOP: "is a loop of symbolic links",
               errno.EIO: "cannot be read (input/output error of the disk)"}
    if isinstance(exc, FileNotFoundError):
        return reasons[errno.ENOENT]
    if isinstance(exc, PermissionError):
        return reasons[errno.EACCES]
    if isinstance(exc, IsADirectoryError):
        return reasons[errno.EISDIR]
    return reasons.get(exc.errno) if isinstance(exc.errno, int) else None


def readable_file(path: Any, what: str = "file") -> Path:
    """The path of an existing, readable regular file, or an :class:`InputError` saying why not.

    Parameters
    ----------
    path : path-like
        The user's path.
    what : str
        What the file is, for the message (``"history file"``, ``"wear table"`` ...).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    InputError
        The path is empty, does not exist, is a directory, has a name too long, is not readable.

    Examples
    --------
    >>> import tempfile
    >>> d = tempfile.mkdtemp()
    >>> try:
    ...     readable_file(d, "history file")
    ... except InputError as exc:
    ...     print(str(exc).split("' ")[1])
    is a directory, not a file
    """
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"{what}: expected a file path, got {type(path).__name__} {path!r}")
    text = os.fspath(path)
    if isinstance(text, bytes):
        text = os.fsdecode(text)
    if not text.strip() or "\x00" in text:
        raise InputError(f"{what} {text!r}: not a valid file name")
    p = Path(text)
    try:
        mode = p.stat().st_mode
    except OSError as exc:
        reason = _os_problem(exc) or f"cannot be read ({exc.strerror or exc})"
        raise InputError(f"{what} {text!r} {reason}") from None
    except ValueError as exc:  # e.g. an embedded NUL on some platforms
        raise InputError(f"{what} {text!r}: not a valid file name ({exc})") from None
    if stat.S_ISDIR(mode):
        raise InputError(f"{what} {text!r} is a directory, not a file")
    if stat.S_ISFIFO(mode):
        # a pipe without a writer blocked the reader forever; one whose writer is done before
        # the reader opens it loses what it sent (issue 29): files only
        raise InputError(f"{what} {text!r} is a named pipe (FIFO), not a file: reading it can "
                         "block forever; save the stream to a file and give that file")
    if not stat.S_ISREG(mode):
        raise InputError(f"{what} {text!r} is not a regular file (a device or socket); give "
                         "the path of a file")
    if not os.access(p, os.R_OK):
        raise InputError(f"{what} {text!r} cannot be read (permission denied): check its "
                         "permissions")
    return p


class reading:  # noqa: N801 - a context manager used as a function, ``with reading(...)``
    """Turn whatever the parsing of ``path`` raises into a fretwear error naming the file.

    fretwear errors pass unchanged. Operating-system errors (permission, a directory, a name
    too long, a disk error) become :class:`InputError`; damaged content (truncated gzip or zip,
    bad encoding, no data, a corrupt binary file: see the module docstring) becomes
    :class:`FormatError` ``"<path>: damaged or truncated <format> file (<what went wrong>)"``.
    Other exceptions of formats parsed in Python pass unchanged (they are bugs of fretwear).

    A class rather than a generator context manager: a bundle's file enters three of them
    (its format, its open, its blocks) and a generator's costs some 3 µs to enter and leave,
    this one a tenth of it (issue 28); nothing is done unless an exception leaves the block.

    Parameters
    ----------
    path : path-like or str
        The user's file (or a label), quoted in the message.
    format : str
        Its format (``csv``, ``aster``, ``parquet``, ``hdf5``, ``netcdf``, ``npz``, ``toml`` ...).
    what : str
        What the file is, for operating-system errors.
    """

    __slots__ = ("path", "format", "what")

    def __init__(self, path: Any, format: str, what: str = "file") -> None:
        self.path, self.format, self.what = path, format, what

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind, exc, traceback) -> bool:
        if exc is not None and isinstance(exc, Exception) and not isinstance(exc, FretwearError):
            path = self.path
            label = os.fspath(path) if isinstance(path, os.PathLike) else str(path)
            _translate(exc, label, self.format, self.what)
        return False  # anything else propagates unchanged


def _translate(exc: Exception, label: str, format: str, what: str) -> None:
    """Raise the fretwear error of an exception a file's parsing raised (:class:`reading`),
    or return when it is none of a damaged file's (it then propagates unchanged)."""
    if isinstance(exc, OSError):
        reason = _os_problem(exc)
        if reason is not None:
            name = exc.filename if isinstance(exc.filename, str) else label
            if os.path.basename(name).startswith(".") and name.endswith(".tmp"):
                name = label  # never the name of an atomic writer's temporary file
            raise InputError(f"{what} {name!r} {reason}") from exc
        raise FormatError(f"{label}: damaged or truncated {format} file ({_describe(exc)}); "
                          "write it again or check the transfer") from exc
    # the errors of a damaged file (pandas' once pandas is imported: taken at the error)
    if not isinstance(exc, _DAMAGED + _pandas_errors()
                      + (_LIBRARY if format in BINARY_FORMATS else ())):
        return
    if isinstance(exc, UnicodeError):
        raise FormatError(f"{label}: not {format} text in the expected encoding "
                          f"({_describe(exc)}); save it as UTF-8, or give its encoding "
                          "(reader option encoding=..., e.g. 'latin-1')") from exc
    raise FormatError(f"{label}: damaged or truncated {format} file ({_describe(exc)}); "
                      "write it again or check the transfer") from exc


def _describe(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    text = text[:300]
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


# --------------------------------------------------------------------------- memory
#: Size [bytes] above which streaming a format that is read whole (NPZ, Code_Aster text, a set
#: of IMPR_FONCTION files) warns: its memory grows with the file, not with ``chunk_size``.
WHOLE_READ_WARNING_BYTES = 256 * 2**20


def warn_whole_read(files: list, label: str, format: str) -> None:
    """Warn (:class:`WholeReadWarning`) when ``files``, about to be read whole although
    streaming was asked, exceed :data:`WHOLE_READ_WARNING_BYTES` together."""
    size = sum(os.path.getsize(f) for f in files
               if isinstance(f, (str, os.PathLike)) and os.path.isfile(f))
    if size > WHOLE_READ_WARNING_BYTES:
        warnings.warn(
            f"{label}: {size / 2**20:.0f} MiB of {format} data are read whole (this format "
            "cannot be streamed; memory grows with the file, not with chunk_size); convert it "
            "once to Parquet, HDF5 or CSV to stream it with bounded memory: "
            "fretwear.io.write_history(read_history(path), 'history.parquet')",
            WholeReadWarning, stacklevel=4)


# --------------------------------------------------------------------------- HDF5 / NetCDF
_PROBED: dict[tuple, dict] = {}

_CHILD = r"""
import json, signal, sys
signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's: it ends this on EOF


def check(path, fmt):
    info = {}
    if fmt == "hdf5":
        def touch(obj):
            for k in list(obj.attrs):
                obj.attrs[k]
            if isinstance(obj, h5py.Dataset):
                obj.shape, obj.dtype
                if obj.ndim == 1 and obj.shape[0]:
                    obj[0]; obj[obj.shape[0] - 1]
        with h5py.File(path, "r") as f:
            info["netcdf"] = "_NCProperties" in f.attrs
            touch(f)
            f.visititems(lambda name, obj: touch(obj))
    else:
        with netCDF4.Dataset(path, "r") as ds:
            def walk(g):
                for k in g.ncattrs():
                    g.getncattr(k)
                for d in g.dimensions.values():
                    len(d)
                for v in g.variables.values():
                    v.dimensions, v.dtype, v.shape
                    for k in v.ncattrs():
                        v.getncattr(k)
                    if v.ndim == 1 and v.shape[0]:
                        v[0]; v[v.shape[0] - 1]
                for sub in g.groups.values():
                    walk(sub)
            walk(ds)
    return info


for line in sys.stdin:
    path, fmt = json.loads(line)
    try:
        if fmt == "hdf5":
            import h5py
        else:
            import netCDF4
    except Exception as exc:
        answer = {"import": repr(exc)}
    else:
        try:
            answer = check(path, fmt)
        except BaseException as exc:
            answer = {"error": f"{type(exc).__name__}: {exc}"[:300]}
    sys.stdout.write(json.dumps(answer) + "\n")
    sys.stdout.flush()
"""


class _Checker:
    """A long-lived child process (``sys.executable`` running :data:`_CHILD`) that walks the
    files it is sent, one JSON line ``[path, format]`` in, one JSON line out.

    One per process (:func:`_checker`): a bundle's worker starts it once for all its files
    (a child per file cost about 0.2 s a file: Python's start and h5py's import), a
    single-contact command once for its files. A file that makes the library crash kills this
    child, not the caller; a hang is cut after :data:`PROBE_TIMEOUT` seconds by killing it; the
    next file starts a new one. It ends when its caller's process ends (end of its input).
    """

    def __init__(self) -> None:
        self.script = _CHILD
        self.owner = os.getpid()
        self.process = subprocess.Popen([sys.executable, "-c", self.script],
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                        stderr=subprocess.DEVNULL, text=True, bufsize=1)
        self.answers: queue.SimpleQueue = queue.SimpleQueue()
        threading.Thread(target=self._listen, name="fretwear-probe", daemon=True).start()

    def _listen(self) -> None:
        for line in self.process.stdout:
            self.answers.put(line)
        self.answers.put(None)  # the child ended

    def ask(self, path: Path, format: str, timeout: float) -> str | None:
        """The child's answer line, or None when it died (its exit status in
        ``self.process.returncode``); :class:`TimeoutError` after ``timeout`` seconds."""
        try:
            self.process.stdin.write(json.dumps([os.path.abspath(path), format]) + "\n")
            self.process.stdin.flush()
        except OSError:  # it had died: its end-of-output is queued
            pass
        try:
            line = self.answers.get(timeout=timeout)
        except queue.Empty:
            raise TimeoutError from None
        if line is None:
            self.process.wait()
        return line

    def close(self) -> None:
        with contextlib.suppress(OSError):
            self.process.kill()
        with contextlib.suppress(OSError, subprocess.SubprocessError):
            self.process.wait(timeout=5)
        for stream in (self.process.stdin, self.process.stdout):
            with contextlib.suppress(OSError):
                stream.close()


_CHECKER: _Checker | None = None
_CHECKER_LOCK = threading.Lock()


def _checker() -> _Checker:
    """This process's checker (started on first use; again after a crash, a hang, a fork or a
    change of :data:`_CHILD`)."""
    global _CHECKER
    old = _CHECKER
    if old is not None and old.owner == os.getpid() and old.script == _CHILD \
            and old.process.poll() is None:
        return old
    if old is not None and old.owner == os.getpid():
        old.close()
    _CHECKER = _Checker()
    return _CHECKER


def _drop_checker() -> None:
    global _CHECKER
    if _CHECKER is not None and _CHECKER.owner == os.getpid():
        _CHECKER.close()
    _CHECKER = None


atexit.register(_drop_checker)


def _check_hdf5_superblock(path: Path, size: int) -> None:
    """Signature (at 0, 512, 1024 ...) and the end-of-file address against the file's size."""
    with open(path, "rb") as handle:
        offset = 0
        while True:
            handle.seek(offset)
            head = handle.read(96)
            if head[:8] == HDF5_MAGIC:
                break
            offset = 512 if offset == 0 else offset * 2
            if offset >= size:
                raise FormatError(f"{path}: not a readable HDF5 file (no HDF5 signature: "
                                  "not an HDF5 or NetCDF-4 file)")
    if len(head) < 12:
        raise FormatError(f"{path}: truncated HDF5 file ({size} bytes: the superblock is cut)")
    version = head[8]
    if version in (0, 1):
        width, at = head[13], 24  # base, free-space, end-of-file addresses
        skip = 2
    elif version in (2, 3):
        width, at = head[9], 12  # base, superblock extension, end-of-file addresses
        skip = 2
    else:
        raise FormatError(f"{path}: HDF5 superblock version {version} is unknown (0 to 3); "
                          "the file is damaged")
    if width not in (2, 4, 8, 16):
        raise FormatError(f"{path}: HDF5 superblock declares {width}-byte addresses; the file "
                          "is damaged")
    if width == 16 or len(head) < at + (skip + 1) * width:
        return
    start = at + skip * width
    eof = int.from_bytes(head[start:start + width], "little")
    base = int.from_bytes(head[at:at + width], "little")
    undefined = (1 << (8 * width)) - 1
    if eof != undefined and base != undefined and base + eof > size:
        raise FormatError(f"{path}: truncated HDF5 file: it holds {size} bytes but its "
                          f"superblock says {base + eof}; the copy or the write was cut short")


def _check_netcdf_classic(path: Path, size: int) -> None:
    """A classic NetCDF header is at least 32 bytes (magic, record count, three lists)."""
    if size < 32:
        raise FormatError(f"{path}: truncated NetCDF file ({size} bytes: the header is cut)")


def probe(path: str | os.PathLike, format: str) -> dict:
    """Check an HDF5 or NetCDF file before the C library opens it in this process.

    The signature and the size declared by the superblock are checked here; then this process's
    checking child (long-lived, started on the first file: one per bundle worker, one per
    command) opens the file, reads every attribute, the shape and the first and last value of
    every 1-D dataset or variable. A child that crashes on the file (segmentation fault), or
    runs longer than :data:`PROBE_TIMEOUT` seconds on it (it is then killed), or a library that
    raises, makes a :class:`FormatError` here; the next file gets a new child. The outcome is
    remembered for the file's (path, size, modification time).

    Parameters
    ----------
    path : path-like
        The file.
    format : {"hdf5", "netcdf"}
        The library that will open it.

    Returns
    -------
    dict
        ``{"netcdf": bool}`` for HDF5 (whether the root holds ``_NCProperties``: a NetCDF-4
        file); ``{}`` otherwise, or when the child could not run (no library: the reader then
        names the missing extra).

    Raises
    ------
    FormatError
        The file is truncated, damaged, or makes the library crash, fail or hang.
    """
    p = Path(path)
    st = p.stat()
    key = (str(p.resolve()), st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns, format)
    if key in _PROBED:
        return dict(_PROBED[key])
    with open(p, "rb") as handle:
        head = handle.read(8)
    if head[:8] == HDF5_MAGIC or format == "hdf5":
        _check_hdf5_superblock(p, st.st_size)
    elif head[:4] in NETCDF_CLASSIC_MAGIC:
        _check_netcdf_classic(p, st.st_size)
    library = "HDF5" if format == "hdf5" else "NetCDF"
    with _CHECKER_LOCK:
        try:
            checker = _checker()
        except OSError:  # no interpreter to run the check: let the library open it
            return {}
        try:
            line = checker.ask(p, format, PROBE_TIMEOUT)
        except TimeoutError:
            _drop_checker()
            raise FormatError(f"{p}: the {library} library did not finish reading the file's "
                              f"structure in {PROBE_TIMEOUT:g} s: the file is damaged (a "
                              "corrupt attribute or index makes the library loop)") from None
        if line is None:  # the checker died on this file
            status = checker.process.returncode
            _drop_checker()
            try:
                how = signal.Signals(-status).name if status < 0 else f"exit status {status}"
            except ValueError:
                how = f"signal {-status}"
            raise FormatError(f"{p}: the {library} library crashed ({how}) reading this file: "
                              "it is damaged; write it again or check the transfer")
    try:
        info = json.loads(line)
    except json.JSONDecodeError:
        info = {}
    if "error" in info:
        raise FormatError(f"{p}: not a readable {format} file ({info['error']})")
    if "import" in info:
        return {}
    if len(_PROBED) > 256:
        _PROBED.clear()
    _PROBED[key] = info
    return dict(info)
