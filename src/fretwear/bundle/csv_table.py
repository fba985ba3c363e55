"""The bundle's CSV table written as pandas writes it, byte for byte, faster
(:func:`write_csv`: each column's distinct values formatted once, the lines joined by pyarrow)."""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear.table.schema import FLOAT_FORMAT

_SPECIAL = re.compile('[,"\r\n]')  # a field holding one is quoted by the csv module


def write_csv(frame: pd.DataFrame, path: Path) -> bool:
    """Write ``frame`` as ``frame.to_csv(path, index=False, float_format=FLOAT_FORMAT)`` does,
    byte for byte, faster: each column's distinct values are formatted once (a float by its
    bits: ``-0.0`` is not ``0.0``) and the lines joined by pyarrow; False (nothing written)
    for a frame it does not know to write as pandas does (a column of dates, a float32, an
    index of several levels, no pyarrow).

    A bundle's table repeats most values (instants, durations, origins, sector angles, a
    worn volume of 0: the CSV table of 20 000 contacts was 506 MB written in 57 s by pandas,
    whose per-value formatting in Python was most of it)."""
    pa = _pyarrow()
    if pa is None or frame.columns.nlevels != 1:
        return False
    arrays = []
    for name in frame.columns:
        text = _column_text(frame[name], pa if len(frame.columns) > 1 else None)
        if text is None:
            return False
        codes, uniques = text
        if len(frame.columns) == 1:  # the csv module quotes a row's only field when empty
            uniques = ['""' if t == "" else t for t in uniques]
        uniques = uniques if isinstance(uniques, pa.Array) else pa.array(uniques,
                                                                         type=pa.large_string())
        arrays.append(pa.compute.take(uniques, pa.array(codes, type=pa.int64())))
    header = io.StringIO()
    csv.writer(header, lineterminator="\n").writerow([str(c) for c in frame.columns])
    with open(path, "wb") as handle:
        handle.write(header.getvalue().encode("utf-8"))
        if not arrays or not len(frame):
            return True
        # each line with its end: the columns joined by ",", then the line and "" by "\n"
        text = pa.large_string()
        lines = pa.compute.binary_join_element_wise(*arrays, pa.scalar(",", text))
        lines = pa.compute.binary_join_element_wise(lines, pa.scalar("", text),
                                                    pa.scalar("\n", text))
        for chunk in lines.chunks if isinstance(lines, pa.ChunkedArray) else [lines]:
            offsets = np.frombuffer(chunk.buffers()[1], dtype=np.int64)[
                chunk.offset:chunk.offset + len(chunk) + 1]
            handle.write(memoryview(chunk.buffers()[2])[offsets[0]:offsets[-1]])
    return True


def _pyarrow():
    try:
        import pyarrow as pa
        import pyarrow.compute  # noqa: F401 - pa.compute
    except ImportError:
        return None
    return pa


def _column_text(values: pd.Series, pa=None) -> tuple[np.ndarray, list[str]] | None:
    """``(codes, texts)``: each row's text in the CSV as ``texts[codes]``, as pandas writes it
    (a float64 by :data:`FLOAT_FORMAT`, a missing value empty, a text quoted where the csv
    module quotes it); None for a dtype not written here. With ``pa`` (pyarrow), the texts
    of NumPy integers and of texts none of which is quoted are a pyarrow array, made without
    a Python string per value (the summary's 10^5 contact ids, history paths and ranks)."""
    dtype = values.dtype
    if dtype == np.float64:
        bits = values.to_numpy().view(np.int64)
        codes, uniques = pd.factorize(bits, sort=False)
        floats = uniques.view(np.float64).tolist()
        return codes, ["" if f != f else FLOAT_FORMAT % f for f in floats]
    if dtype.kind not in "iubO" and not isinstance(dtype, pd.StringDtype | pd.BooleanDtype) \
            and not (isinstance(dtype, pd.api.extensions.ExtensionDtype)
                     and dtype.kind in "iu"):
        return None
    codes, uniques = pd.factorize(values, sort=False, use_na_sentinel=True)
    texts = None if pa is None else _arrow_texts(uniques, dtype, pa)
    if texts is not None:
        codes = np.asarray(codes, dtype=np.int64)
        if (codes < 0).any():  # missing: written empty
            texts = pa.concat_arrays([texts, pa.array([""], type=pa.large_string())])
            codes = np.where(codes < 0, len(texts) - 1, codes)
        return codes, texts
    texts = []
    for v in uniques.tolist() if hasattr(uniques, "tolist") else list(uniques):
        if isinstance(v, float | np.floating) or not isinstance(v, str | int | bool | np.integer
                                                                    | np.bool_):
            return None  # pandas formats a float among objects its own way: left to it
        texts.append(_quoted(str(v)))
    codes = np.asarray(codes, dtype=np.int64)
    if (codes < 0).any():  # missing: written empty
        texts.append("")
        codes = np.where(codes < 0, len(texts) - 1, codes)
    return codes, texts


def _arrow_texts(uniques, dtype, pa):
    """The texts of distinct NumPy integers (``str(int)``: pyarrow's cast writes the same
    digits) or of distinct texts none of which the csv module quotes (as they are), as a
    pyarrow large_string array; None otherwise (the caller's loop decides)."""
    if isinstance(dtype, np.dtype) and dtype.kind in "iu":
        return pa.array(np.asarray(uniques)).cast(pa.large_string())
    if not isinstance(dtype, pd.StringDtype):
        return None
    texts = pa.array(uniques)  # pyarrow's own strings where pandas holds them so
    if not pa.types.is_string(texts.type) and not pa.types.is_large_string(texts.type):
        return None
    texts = texts.cast(pa.large_string())
    if texts.null_count or pa.compute.any(
            pa.compute.match_substring_regex(texts, _SPECIAL.pattern)).as_py():
        return None
    return texts


def _quoted(text: str) -> str:
    """``text`` as the csv module writes one field of a row of several (QUOTE_MINIMAL)."""
    if _SPECIAL.search(text) is None:
        return text
    if "\r" not in text:  # quoted by every Python's csv module: in quotes, quotes doubled
        return '"' + text.replace('"', '""') + '"'
    # a lone CR is quoted by some Python versions' csv module only: asked (the bytes checked
    # against pandas in tests/bundle/test_bundle_files.py)
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerow([text, ""])
    return out.getvalue()[:-2]
