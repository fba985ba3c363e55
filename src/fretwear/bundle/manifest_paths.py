"""Where a manifest's files are: each relative path cell made absolute, as ``Path.resolve``
makes it (an absolute cell is kept as written, ``str(Path(cell))``: its links too).

A manifest of 10^5 histories in one folder spent 0.8 s of the client's CPU in
:func:`fretwear.bundle.read_manifest` before any worker started (issue 28), half of it on
the paths: a ``Path`` per row, a ``lstat`` per file (is it a link?), ``os.path.join``.
:class:`HistoryPaths` resolves each folder once and, for a folder holding many of the
manifest's files, asks its listing once (``os.scandir``: each entry's type comes with the
listing) which of them are links; every other case goes the way :func:`absolute` goes.
"""

from __future__ import annotations

import os
import stat
from collections import Counter
from pathlib import Path
from typing import Any

#: A folder holding at least this many of a manifest's files is listed once
#: (:class:`HistoryPaths`), not looked at a file at a time.
LISTED_FROM = 256
#: The listing is given up (each file then looked at alone) past this many entries for each of
#: the manifest's files in the folder: a few files of a folder of millions cost no listing.
LISTING_SPAN = 4


def absolute(value: Any, directory: Path) -> Any:
    """``(directory / value).resolve()`` as text (a list element by element); a path that
    cannot be resolved is left as written (:func:`resolved`)."""
    if isinstance(value, list):
        return [absolute(v, directory) for v in value]
    p = Path(str(value))
    return str(p) if p.is_absolute() else resolved(directory / p)


def resolved(path: Path) -> str:
    """``path`` resolved, or as written when it cannot be (a loop of links: a RuntimeError on
    Python < 3.13; a NUL byte: a ValueError): the contact's reader then fails with a fretwear
    error naming it (:func:`fretwear.io.guard.readable_file`), the other contacts go on."""
    try:
        return str(path.resolve())
    except (OSError, RuntimeError, ValueError):
        return str(path)


class HistoryPaths:
    """The absolute paths of a manifest's ``history`` cells (relative to ``directory``), the
    text :func:`absolute` gives of each: a relative cell resolved (``Path.resolve``), an
    absolute one as written (``str(Path(cell))``, its links kept: the task keys of earlier
    runs are made of that text).

    Each folder is resolved once; a file in a resolved folder is its folder and its name,
    unless it is a link (then resolved whole). Whether it is one is read from the folder's
    listing when the folder holds :data:`LISTED_FROM` of the cells or more, else from a
    ``lstat`` of the file; a name the listing lacks (missing, or made since) gets its
    ``lstat``, and a file ``lstat`` cannot look at (missing, too long, no permission) is
    left to ``Path.resolve``, which ignores those errors: that contact fails alone when its
    file is read.

    Parameters
    ----------
    texts : list of str
        The cells (empty ones left out by the caller).
    directory : Path
        The manifest's folder (absolute).
    """

    def __init__(self, texts: list[str], directory: Path) -> None:
        self.directory = directory
        self.parents: dict[str, str | None] = {}  # head -> resolved folder (None: cannot be)
        counts = Counter(os.path.split(t)[0] for t in texts if not os.path.isabs(t))
        self.listed = {head for head, n in counts.items() if n >= LISTED_FROM}
        self.counts = counts
        self.links: dict[str, dict[str, bool] | None] = {}  # folder -> {name: is a link}

    def __call__(self, text: str) -> str:
        """The absolute path of the cell ``text``."""
        if os.path.isabs(text):
            return str(Path(text))
        head, name = os.path.split(text)
        if name in ("", ".", ".."):  # a trailing slash, "." or "..": Path.resolve's
            return resolved(self.directory / text)
        folder = self.parents.get(head, False)
        if folder is False:
            try:
                folder = str((self.directory / head).resolve())
            except (OSError, RuntimeError, ValueError):  # a link loop, a NUL: the reader says
                folder = None
            self.parents[head] = folder
        if folder is None:
            return resolved(self.directory / text)
        target = folder + name if folder.endswith(os.sep) else folder + os.sep + name
        link = self._listed_link(head, folder, name)
        if link is None:
            try:
                link = stat.S_ISLNK(os.lstat(target).st_mode)
            except (OSError, ValueError):  # Path.is_symlink would raise ENAMETOOLONG, EACCES
                return resolved(self.directory / text)
        return resolved(Path(target)) if link else target

    def _listed_link(self, head: str, folder: str, name: str) -> bool | None:
        """Whether ``name`` is a link by its folder's listing; None: not known from it."""
        if head not in self.listed:
            return None
        listing = self.links.get(folder, False)
        if listing is False:
            listing = self.links[folder] = _listing(folder, LISTING_SPAN * self.counts[head])
        return None if listing is None else listing.get(name)


def _listing(folder: str, most: int) -> dict[str, bool] | None:
    """``{name: is a link}`` of the entries of ``folder``; None where it cannot be listed or
    holds more than ``most`` entries."""
    out: dict[str, bool] = {}
    try:
        with os.scandir(folder) as entries:
            for entry in entries:
                if len(out) >= most:
                    return None
                out[entry.name] = entry.is_symlink()
    except OSError:
        return None
    return out
