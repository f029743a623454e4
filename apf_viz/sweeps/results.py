"""The results table: one row per run, Parquet or CSV by the file's extension, written atomically and
resumed (a table this sweep did not write is refused, never overwritten)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from apf_viz.core.files import check_readable, replace_atomically, write_atomic
from apf_viz.core.formats import InputError
from apf_viz.sweeps.cells import _LATER_COLUMNS, COLUMNS, KEY


def read_results(path: Path) -> list[dict]:
    """The rows of a results table, or [] when there is none; a file that is not a table this sweep
    wrote (another CSV, a Parquet file with other columns, notes) is refused, never overwritten."""
    if not path.exists():
        return []
    check_readable(path)  # a FIFO would block the reader
    try:
        if path.suffix == ".csv":
            import csv

            with path.open(newline="", encoding="utf-8") as f:
                reader = csv.DictReader(f)
                _check_columns(path, reader.fieldnames or [])
                return [_typed({**_LATER_COLUMNS, **r}) for r in reader]
        import pyarrow.parquet as pq

        table = pq.read_table(path)
        _check_columns(path, table.column_names)
        return [{**_LATER_COLUMNS, **r} for r in table.to_pylist()]
    except InputError:
        raise
    except Exception as e:  # a file that is not a results table: say so rather than overwrite it
        raise InputError(
            f"{path}: not a results table this sweep can resume ({type(e).__name__}: {e})"
        ) from None


def _check_columns(path: Path, columns: Sequence[str]) -> None:
    missing = [c for c in COLUMNS if c not in columns and c not in _LATER_COLUMNS]
    extra = [c for c in columns if c not in COLUMNS]
    if missing or extra:
        what = f"missing columns {', '.join(missing)}" if missing else ""
        what += ("; " if missing and extra else "") + (
            f"columns it does not write: {', '.join(extra)}" if extra else ""
        )
        raise InputError(f"{path}: not a results table of apf-viz sweep ({what}); choose another --out")


def _typed(r: dict) -> dict:
    ints = ("k", "D", "seed", "moves", "events", "cycles", "lights_used", "hidden")
    floats = ("moves_per_kD", "wall_s")
    return {c: (int(v) if c in ints else float(v) if c in floats else v) for c, v in r.items()}


def write_results(path: Path, rows: list[dict]) -> None:
    rows = sorted(rows, key=lambda r: tuple(str(r[c]) for c in KEY))
    if path.suffix == ".csv":
        import csv
        import io

        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=list(COLUMNS))
        w.writeheader()
        w.writerows(rows)
        write_atomic(path, buf.getvalue())
        return
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.Table.from_pylist(rows, schema=_schema()) if rows else _schema().empty_table()
    replace_atomically(path, lambda tmp: pq.write_table(table, tmp))


def _schema():
    import pyarrow as pa

    types = {"moves_per_kD": pa.float64(), "wall_s": pa.float64()}
    text = ("scheduler", "algorithm", "light_semantics", "start", "outcome", "trace", "error")
    return pa.schema([(c, types.get(c, pa.string() if c in text else pa.int64())) for c in COLUMNS])
