"""The output directory of a bundle run: parts written as contacts finish, and the final files.

Layout of ``OUT/``::

    parts/part-<run>-<n>.parquet   rows of the contacts of part n (``contact`` + wear columns)
    parts/part-<run>-<n>.json      one record per contact of that part: input key, status,
                                   warnings, error, samples, compute time, table metadata
                                   (what contacts share written once: part_json)
    table.parquet | table.csv      every contact's wear table, identity columns in front
    dataset.zarr | dataset.nc      the same as an xarray Dataset (contact × instant × sector)
    errors.csv, warnings.csv, summary.csv, run.json

A part's rows are written first and its JSON last, both atomically (temporary file + rename), so
a part exists only once complete: a run killed at any moment leaves whole parts. The next run
reads the JSON records, skips every contact whose input key is unchanged and whose status was
``done``, and recomputes the others (``force=True`` recomputes all). A contact that fails
when recomputed (its history moved, unreadable) keeps its earlier record and rows: it is
reported ``stale`` and its failed record is not written, so no rerun loses a result.
"""

from __future__ import annotations

import glob
import json
import os
import shutil
import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from fretwear._lazy import pandas as pd
from fretwear._optional import optional
from fretwear.bundle.datasets import path_stamp, require
from fretwear.bundle.part_json import part_text, records_of
from fretwear.bundle.rows_files import (  # noqa: F401 - read_frame, write_frame: their home until now
    read_frame,
    write_frame,
    write_rows,
)
from fretwear.bundle.table_file import PrefixTable, read_columns, read_part_file, stream_table
from fretwear.errors import InputError
from fretwear.io.atomic import atomic_path, atomic_write, remove_stale_in

TABLE_FORMATS = ("parquet", "csv")
#: Marker file of a run's ``parts/`` that workers check (``.shared-<token>``, worker_parts).
MARKER = ".shared-"
DATASET_FORMATS = ("zarr", "netcdf")


def _split(frame: pd.DataFrame, names: list[str], where: dict[str, Any]
           ) -> dict[str, pd.DataFrame]:
    """``{contact: DataFrame of the columns `names` at its row positions}``."""
    columns = [frame[n].array for n in names]
    return {contact: pd.DataFrame({n: c[index] for n, c in zip(names, columns, strict=True)})
            for contact, index in where.items()}


class OutputDirectory:
    """Parts and final files of one bundle output directory.

    Parameters
    ----------
    path : path-like
        The directory (created).
    table_format : str
        ``"parquet"`` or ``"csv"`` for the parts and the final table.
    """

    def __init__(self, path: str | os.PathLike, *, table_format: str = "parquet") -> None:
        if table_format not in TABLE_FORMATS:
            raise InputError(f"table format {table_format!r}: choose one of {TABLE_FORMATS}")
        self.path = Path(path)
        if self.path.exists() and not self.path.is_dir():
            raise InputError(f"output {str(self.path)!r} exists and is not a directory; give a "
                             "directory for the bundle's results")
        self.parts = self.path / "parts"
        self.parts.mkdir(parents=True, exist_ok=True)
        self.table_format = table_format
        self._run = f"{time.time_ns():020d}"
        self._seq = 0
        #: Final files an earlier run recorded in its run.json (``outputs``): the only ones a
        #: later run of another format removes as stale (a file of the user's own is kept).
        self.written_before = self._recorded_outputs()
        #: Final files this run wrote, recorded in its run.json.
        self.written: list[str] = []
        self._shared: dict = {}  # compact(): one object for equal metadata values
        #: The dataset written with the table while the results arrived (finish_table).
        self.zarr_parts = None

    def _recorded_outputs(self) -> set[str]:
        try:
            data = json.loads((self.path / "run.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return set()
        outputs = data.get("outputs") if isinstance(data, dict) else None
        return {str(o) for o in outputs} if isinstance(outputs, list) else set()

    def stamps(self, names: Iterable[str]) -> dict[str, list]:
        """``{name: its stamp}`` of final files (size and modification time; for the Zarr
        directory, its files' count, total size and latest time: :func:`path_stamp`)."""
        return {name: list(path_stamp(self.path / name)) for name in names}

    def unchanged(self, digest: str) -> bool:
        """Whether the final files an earlier run recorded in its run.json are those of
        ``digest`` (:func:`fretwear.bundle.outputs.outputs_digest`: the same records, manifest
        identity and output options) and every one is still there as written (its stamp
        recorded beside it: a file removed, replaced or edited since is written again)."""
        try:
            data = json.loads((self.path / "run.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return False
        if not isinstance(data, dict) or data.get("digest") != digest:
            return False
        recorded = data.get("stamps")
        outputs = [o for o in data.get("outputs") or [] if o != "run.json"]
        if not isinstance(recorded, dict) or not outputs or set(recorded) != set(outputs):
            return False
        return self.stamps(outputs) == recorded

    def _remove_stale(self, name: str) -> None:
        """Remove ``name``, the other format's table or dataset, if an earlier run of this
        directory wrote it (its run.json says so)."""
        if name not in self.written_before:
            return
        stale = self.path / name
        if stale.is_dir() and not stale.is_symlink():
            shutil.rmtree(stale, ignore_errors=True)
        else:
            stale.unlink(missing_ok=True)

    def previous(self) -> dict[str, dict[str, Any]]:
        """The latest record of every contact in the existing parts (``part`` = its stem)."""
        out: dict[str, dict[str, Any]] = {}
        for js in sorted(self.parts.glob("part-*.json")):
            try:
                data = json.loads(js.read_text(encoding="utf-8"))
            except (OSError, json.JSONDecodeError):
                continue  # not a part this code wrote whole: ignored, its contacts recomputed
            for rec in records_of(data):
                out[rec["contact"]] = {**rec, "part": data["part"],
                                       "rows_file": data.get("rows_file"),
                                       "attrs": self.compact(rec.get("attrs"))}
        return out

    def new_stem(self) -> str:
        """The next part's stem (``part-<run>-<n>``: the parts of a run sort in order)."""
        stem = f"part-{self._run}-{self._seq:06d}"
        self._seq += 1
        return stem

    def share_with_workers(self) -> str:
        """Write the marker by which a worker knows it sees this directory
        (:mod:`fretwear.bundle.worker_parts`); returns its token. Written once a run, whole
        (a temporary file renamed over it): the engine asks for it at each wave while the
        workers read it for the groups of the earlier ones, and a rewrite in place let a worker
        read it empty now and then (that group's rows then came back to the client, which
        wrote them after the last result, issue 28)."""
        token = f"{self._run}-{os.getpid()}"
        marker = self.parts / f"{MARKER}{token}"
        if not marker.is_file():
            tmp = marker.with_name(f"{marker.name}.{os.getpid()}.tmp")
            tmp.write_text(token, encoding="utf-8")
            os.replace(tmp, marker)
        return token

    def write_part(self, records: list[dict[str, Any]]) -> str:
        """Write one part (rows, then records); returns its stem."""
        stem = self.new_stem()
        rows_file = f"{stem}.{self.table_format}"
        written = write_rows(records, self.parts / rows_file, self.table_format)
        return self.record_part(records, stem, rows_file if written else None)

    def record_part(self, records: list[dict[str, Any]], stem: str, rows_file: str | None
                    ) -> str:
        """Write the JSON of the part ``stem`` whose rows file ``rows_file`` (in ``parts/``)
        is written: the part exists from then on; returns ``stem``."""
        seen: dict = {}
        for r in records:  # compacted first: its equal values one object, found so when written
            if isinstance(r.get("attrs"), dict):
                r["attrs"] = self.compact(r["attrs"], seen)
        text = part_text(stem, rows_file, records)
        with atomic_write(self.parts / f"{stem}.json", encoding="utf-8", sweep=False) as handle:
            handle.write(text)
        for r in records:
            r["part"], r["rows_file"] = stem, rows_file
            if "attrs" not in r:  # every kept record has its attrs, as compact() gave them
                r["attrs"] = None
        return stem

    def compact(self, attrs: dict | None, seen: dict | None = None) -> dict | None:
        """A record's table metadata as the client keeps it once in a part: every dict or list
        but the power (each contact's own; its sector powers build the depth models) shared
        with the equal ones of other contacts (the geometry, coefficients, sector edges of a
        bundle's few cases; issue 28: 3.5 kB a contact, 350 MB at 10^5, mostly repeated).

        ``seen`` (one dict for the records of one part) remembers each value object already
        shared: the records of a worker's task arrive sharing their case's objects (one pickle
        keeps them one), so a value is compared by its text once per part, not once per
        contact (the ``repr`` of every value was 30 us of the client's CPU a contact)."""
        if not isinstance(attrs, dict):
            return attrs
        out = {}
        for key, value in attrs.items():
            if key != "power" and isinstance(value, (dict, list)):  # a tuple: half the union's cost
                known = seen.get((key, id(value))) if seen is not None else None
                if known is not None and known[0] is value:
                    value = known[1]
                else:
                    shared = self._shared.setdefault((key, repr(value)), value)
                    if seen is not None:  # the original kept: its id stays its own
                        seen[(key, id(value))] = (value, shared)
                    value = shared
            out[key] = value
        return out

    def rows(self, records: Iterable[Mapping[str, Any]]) -> dict[str, pd.DataFrame]:
        """``{contact: its rows}`` read back from the parts of the given records (a frame per
        contact, its columns and dtypes those of the part without ``contact``)."""
        out: dict[str, pd.DataFrame] = {}
        for frame, names, where in self._parts_of(records):
            out.update(_split(frame, names, where))
        return out

    def packed_rows(self, records: Iterable[Mapping[str, Any]]) -> dict[str, dict[str, Any]]:
        """``{contact: its rows as fretwear.bundle.tasks.pack packs them}`` read back from the
        parts of the given records: each part's columns converted to numpy once and sliced per
        contact (a restart skipping 20 000 contacts took 24 s when every contact's rows became a
        DataFrame first); a part with a nullable column, whose numpy form depends on the rows
        taken, goes through :meth:`rows`."""
        out: dict[str, dict[str, Any]] = {}
        for frame, names, where in self._parts_of(records):
            if any(isinstance(frame[n].dtype, pd.api.extensions.ExtensionDtype)
                   and not pd.api.types.is_string_dtype(frame[n].dtype) for n in names):
                out.update({contact: {"columns": list(names),
                                      "arrays": [table[n].to_numpy() for n in names]}
                            for contact, table in _split(frame, names, where).items()})
                continue
            arrays = [frame[n].to_numpy() for n in names]
            for contact, index in where.items():
                out[contact] = {"columns": list(names), "arrays": [a[index] for a in arrays]}
        return out

    def ordered_rows(self, records: Iterable[Mapping[str, Any]], order: list[str]
                     ) -> pd.DataFrame | None:
        """The rows of the given records read from their Parquet parts, one contact after the
        other in ``order``'s order, each contact's rows as its part holds them, ``contact`` in
        front: the table :func:`fretwear.bundle.tasks.concat_packed` gives of the same rows.
        None when this is not the way (CSV parts; parts of different columns or types, which
        ``concat_packed`` aligns): the caller assembles them from :meth:`packed_rows`.

        The parts are read by pyarrow, a part's rows that are not its contacts' latest (a
        contact recomputed into a later part) dropped and the rest put in order in one ``take``,
        and the result converted to pandas column by column as pyarrow frees them
        (``self_destruct``): the client holds the table about twice at the peak, not once per
        contact's slice, then the table, then its reorder (issue 28: the table of 3 000
        contacts took the client's memory up by 30 kB a contact, the table being 12 kB).
        """
        if self.table_format != "parquet":
            return None
        pa = require("pyarrow", purpose="reading a bundle's Parquet parts")
        import pyarrow.parquet as pq

        by_file: dict[str, set[str]] = {}
        for r in records:
            if r.get("rows_file"):
                by_file.setdefault(r["rows_file"], set()).add(str(r["contact"]))
        position = {c: i for i, c in enumerate(order)}
        tables, positions = [], []
        for name, contacts in by_file.items():
            table = read_part_file(pq, self.parts / name)
            if tables and not table.schema.equals(tables[0].schema):
                return None
            codes = table.column("contact").combine_chunks().dictionary_encode()
            ids = codes.dictionary.to_pylist()
            where = np.array([position[c] if c in contacts and c in position else -1
                              for c in map(str, ids)] + [-1], dtype=np.int64)
            index = codes.indices.fill_null(len(ids)).to_numpy(zero_copy_only=False)
            tables.append(table)
            positions.append(where[index])
        if not tables:
            return None
        rows = np.concatenate(positions)
        kept = np.flatnonzero(rows >= 0)
        take = kept[np.argsort(rows[kept], kind="stable")]
        whole = pa.concat_tables(tables)
        del tables
        whole = whole.take(pa.array(take))
        return whole.to_pandas(self_destruct=True, split_blocks=True)

    def _parts_of(self, records: Iterable[Mapping[str, Any]]):
        """``(frame, wear column names, {contact: row positions})`` of each part file holding
        rows of the given records (only those contacts; positions in the part's order)."""
        by_file: dict[str, set[str]] = {}
        for r in records:
            if r.get("rows_file"):
                by_file.setdefault(r["rows_file"], set()).add(r["contact"])
        for name, contacts in by_file.items():
            frame = read_frame(self.parts / name)
            ids = frame["contact"].astype(str).to_numpy(dtype=object)
            groups = pd.Series(range(len(ids))).groupby(ids, sort=False).indices
            where = {str(c): index for c, index in groups.items() if str(c) in contacts}
            yield frame, [str(c) for c in frame.columns if c != "contact"], where

    def cleanup(self, keep: Iterable[str]) -> None:
        """Remove the parts no current record refers to (superseded by a later run)."""
        keep = set(keep)
        for p in self.parts.glob("part-*"):
            if p.name.split(".")[0] not in keep:
                p.unlink(missing_ok=True)
        for p in self.parts.glob(f"{MARKER}*"):  # the workers' markers (worker_parts)
            p.unlink(missing_ok=True)
        if self.zarr_parts is not None:  # a dataset written with the table, not used
            self.zarr_parts.abort()
            self.zarr_parts = None
        # what a killed run wrote while its results arrived (table_file.PrefixTable,
        # result_dataset.GridZarr): another run's store, a table's temporary file left
        # STALE_SECONDS (the age fretwear.io.atomic's own leftovers are removed at)
        for p in self.path.glob(".dataset.zarr.*.parts*"):
            if self._run not in p.name:
                shutil.rmtree(p, ignore_errors=True)
        remove_stale_in(self.path, f"{glob.escape(self.table_path().name)}.*.tmp")
        # a part's temporaries (its rows, its JSON: written without a sweep each, names never
        # written twice; a listing of parts/ after every write cost 1.6 -> 3.1 ms a write
        # over 2 000 parts)
        remove_stale_in(self.parts, "part-*.tmp")

    def table_path(self) -> Path:
        """The final table's file, ``table.<format>``."""
        return self.path / f"table.{self.table_format}"

    def write_table(self, table: pd.DataFrame) -> Path:
        """Write the bundle's table as ``table.<format>`` (atomically); the table of the other
        format that an earlier run of this directory wrote is removed: it is stale."""
        target = self.table_path()
        write_frame(table, target, self.table_format)
        self._table_written()
        return target

    def stream_table(self, records: list[Mapping[str, Any]], order: list[str],
                     identity: pd.DataFrame) -> bool:
        """Write ``table.parquet`` from the Parquet parts of ``records`` without holding the
        table (:func:`fretwear.bundle.table_file.stream_table`, ``identity`` columns in
        front, contacts in ``order``'s order); False (nothing written) for CSV parts, or
        parts of different columns: the caller assembles the table and :meth:`write_table`."""
        if self.table_format != "parquet" or not stream_table(
                self.parts, self.table_path(), records, order, identity):
            return False
        self._table_written()
        return True

    def table_writer(self, order: list[str], identity: pd.DataFrame,
                     dataset_format: str | None = None) -> PrefixTable | None:
        """The ``table.parquet`` written while the results arrive
        (:class:`fretwear.bundle.table_file.PrefixTable`; contacts in ``order``'s order,
        ``identity`` columns in front), with its ``dataset.zarr`` when the dataset is Zarr
        (``dataset_format`` "zarr", or None with zarr installed:
        :class:`fretwear.bundle.result_dataset.GridZarr`); None for a CSV table."""
        if self.table_format != "parquet":
            return None
        dataset = None
        if dataset_format == "zarr" or (dataset_format is None and optional("zarr")):
            from fretwear.bundle.result_dataset import GridZarr

            dataset = GridZarr(self.path / f".dataset.zarr.{self._run}.parts",
                               np.array([str(c) for c in order]).dtype, _zarr_options())
        return PrefixTable(self.parts, self.table_path(), order, identity, dataset)

    def finish_table(self, writer: PrefixTable | None) -> bool:
        """Put in place the table ``writer`` wrote while the results arrived (its dataset kept
        for :meth:`write_zarr_by_regions`); False (nothing written) where it could not
        (:meth:`PrefixTable.finish`)."""
        if writer is None or not writer.finish():
            return False
        self._table_written()
        self.zarr_parts, writer.dataset = writer.dataset, None  # the store's from now on
        return True

    def _table_written(self) -> None:
        self.written.append(self.table_path().name)
        for other in TABLE_FORMATS:
            if other != self.table_format:
                self._remove_stale(f"table.{other}")

    def drop_dataset(self) -> None:
        """No dataset this run (no contact has rows): the one an earlier run of this directory
        wrote, of either format, is removed (it would stand beside an empty table)."""
        for name in ("dataset.nc", "dataset.zarr"):
            self._remove_stale(name)

    def write_dataset(self, dataset, fmt: str) -> Path:
        """Write the dataset atomically: a NetCDF file, or a Zarr directory swapped in whole;
        the dataset of the other format that an earlier run of this directory wrote is
        removed: it is stale."""
        if fmt not in DATASET_FORMATS:
            raise InputError(f"dataset format {fmt!r}: choose one of {DATASET_FORMATS}")
        self._remove_stale("dataset.zarr" if fmt == "netcdf" else "dataset.nc")
        self.written.append("dataset.nc" if fmt == "netcdf" else "dataset.zarr")
        if fmt == "netcdf":
            target = self.path / "dataset.nc"
            with atomic_path(target) as tmp:
                dataset.to_netcdf(tmp)
            return target
        self._swap_zarr(lambda tmp, **options: dataset.to_zarr(tmp, mode="w", **options))
        return self.path / "dataset.zarr"

    def write_zarr_by_regions(self, contacts: pd.DataFrame) -> bool:
        """Write ``dataset.zarr`` from the written Parquet table a group of contacts at a
        time (:func:`fretwear.bundle.result_dataset.write_zarr_by_regions`), swapped in whole;
        False (nothing written) where that cannot be: :meth:`write_dataset` then."""
        from fretwear.bundle.result_dataset import write_zarr_by_regions

        written, self.zarr_parts = self.zarr_parts, None
        if written is not None and self._swap_zarr(
                lambda tmp, **options: written.finish(contacts, tmp)):
            pass  # written with the table while the results arrived (GridZarr)
        elif not self._swap_zarr(lambda tmp, **options: write_zarr_by_regions(
                self.table_path(), contacts, tmp, **options)):
            return False
        self._remove_stale("dataset.nc")
        self.written.append("dataset.zarr")
        return True

    def _swap_zarr(self, write) -> bool:
        """``write(tmp, **options)`` a Zarr store into a temporary directory, then swap it in
        as ``dataset.zarr``; False (nothing swapped in) where ``write`` returns False."""
        target = self.path / "dataset.zarr"
        tmp = self.path / f".dataset.zarr.{self._run}.tmp"
        shutil.rmtree(tmp, ignore_errors=True)
        try:
            if write(tmp, **_zarr_options()) is False:
                return False
            old = self.path / f".dataset.zarr.{self._run}.old"
            if target.exists():
                os.replace(target, old)
            os.replace(tmp, target)
            shutil.rmtree(old, ignore_errors=True)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        return True


def _zarr_options() -> dict[str, Any]:
    """``Dataset.to_zarr``'s options of ``dataset.zarr``: Zarr format 2 (readable by every zarr
    version; format 3 has no string type yet), metadata consolidated."""
    zarr = require("zarr")
    version2 = {"zarr_format": 2} if int(zarr.__version__.split(".")[0]) >= 3 else {}
    return {"consolidated": True, **version2}


def _part_records(parts: Path) -> dict[str, dict[str, Any]]:
    """The latest record of every contact in ``parts/`` (read only: nothing created)."""
    out: dict[str, dict[str, Any]] = {}
    for js in sorted(parts.glob("part-*.json")) if parts.is_dir() else ():
        try:
            data = json.loads(js.read_text(encoding="utf-8"))
        except (OSError, json.JSONDecodeError):
            continue
        for rec in records_of(data):
            out[str(rec["contact"])] = rec
    return out


def _contacts_frame(table: pd.DataFrame, errors: pd.DataFrame,
                    records: dict[str, dict[str, Any]]) -> pd.DataFrame:
    """One row per contact as :func:`fretwear.bundle.run_bundle` gives it, from the table's
    identity columns (the errors' for a contact without rows) and the parts' records."""
    from fretwear.bundle.manifest import IDENTITY

    ident = [c for c in IDENTITY if c in table.columns]
    identity = table[ident].drop_duplicates("contact") if len(table) else \
        pd.DataFrame(columns=ident)
    if len(errors) and "contact" in errors.columns:
        extra = errors[[c for c in ident if c in errors.columns]]
        identity = pd.concat([identity, extra[~extra["contact"].isin(identity["contact"])]],
                             ignore_index=True)
    identity = identity.assign(contact=identity["contact"].astype(str))
    info = []
    for c in identity["contact"]:
        rec = records.get(c, {})
        attrs = rec.get("attrs") or {}
        info.append({"contact": c, "status": rec.get("status", "done"),
                     "samples": rec.get("samples", 0), "seconds": rec.get("seconds", 0.0),
                     "power": (attrs.get("power") or {}).get("total"),
                     **{k: attrs.get(k) for k in (
                         "time_unit", "origin", "tube_replacement", "wall_thickness",
                         "depth_limit", "contact_type", "dimensions", "law",
                         "coefficients_mobile", "coefficients_obstacle", "time_scale",
                         "sector_coefficients")}})
    return identity.merge(pd.DataFrame(info, columns=["contact"] + list(info[0]) [1:]
                                       if info else ["contact"]), on="contact", how="left")


def load(path: str | os.PathLike):
    """A finished bundle's results, read from its output directory without its history files.

    Read only: nothing is written or created in ``path``. The table is ``table.parquet`` (or
    ``table.csv``), the failures and warnings ``errors.csv`` and ``warnings.csv``, the run's
    statistics ``run.json``, and each contact's record (status, power [W], law, geometry,
    wall thickness [m], depth limit [-], time scale [s per unit]) from ``parts/*.json``, so
    that :meth:`~fretwear.bundle.BundleResult.summary` and the depth models of
    :func:`fretwear.table.depth.models_from_table` work as on the run's own result.

    Parameters
    ----------
    path : path-like
        The ``output=`` directory of :func:`fretwear.bundle.run_bundle` (``fretwear bundle -o``).

    Returns
    -------
    BundleResult
        ``output`` is ``path``; ``stats`` are the run's (``run.json``).

    Raises
    ------
    InputError
        ``path`` is not a directory, or holds no finished run (no ``run.json`` or no table).
    """
    from fretwear.bundle.result import BundleResult

    root = Path(path)
    if not root.is_dir():
        raise InputError(f"{str(root)!r} is not a bundle output directory (fretwear bundle -o "
                         "OUT writes one)")
    tables = [root / f"table.{fmt}" for fmt in TABLE_FORMATS if (root / f"table.{fmt}").is_file()]
    if not (root / "run.json").is_file() or not tables:
        raise InputError(f"{str(root)!r} holds no finished bundle run (no run.json or no "
                         "table.parquet/table.csv): run fretwear bundle -o into it, or let the "
                         "interrupted run finish")
    try:
        stats = json.loads((root / "run.json").read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise InputError(f"{str(root / 'run.json')!r} is not readable JSON ({exc})") from None
    # a Parquet table is read when asked for (BundleResult.table_file), its identity columns
    # alone here: the contacts' frame (issue 28: 1.3 GB at 10^5 contacts)
    lazy = tables[0].suffix == ".parquet"
    from fretwear.bundle.manifest import IDENTITY

    table = read_columns(tables[0], IDENTITY) if lazy else read_frame(tables[0])
    table["contact"] = table["contact"].astype(str)

    def optional_csv(name: str, columns: list[str]) -> pd.DataFrame:
        f = root / name
        frame = read_frame(f) if f.is_file() else pd.DataFrame(columns=columns)
        if "contact" in frame.columns:
            frame["contact"] = frame["contact"].astype(str)
        return frame

    errors = optional_csv("errors.csv", ["contact", "error", "message", "rows_kept"])
    warns = optional_csv("warnings.csv", ["contact", "category", "message"])
    contacts = _contacts_frame(table, errors, _part_records(root / "parts"))
    stats = {k: v for k, v in stats.items() if k != "outputs"} if isinstance(stats, dict) else {}
    return BundleResult(table=None if lazy else table, errors=errors, warnings=warns,
                        contacts=contacts, stats=stats, output=str(root),
                        table_file=str(tables[0]) if lazy else None)
