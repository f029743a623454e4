"""A hunt's table: one row per start (:data:`apf_viz.explore.hunt.COLUMNS`), Parquet, written atomically
and resumed; a file that is not a hunt table is refused, never overwritten."""

from __future__ import annotations

from pathlib import Path

from apf_viz.core.files import check_readable, replace_atomically
from apf_viz.core.formats import InputError
from apf_viz.explore.hunt import COLUMNS, INTEGERS, KEY


def read_hunt(path: Path) -> list[dict]:
    """The rows of a hunt table, or [] when there is none yet."""
    if not path.exists():
        return []
    check_readable(path)
    try:
        import pyarrow.parquet as pq

        table = pq.read_table(path)
    except Exception as e:
        raise InputError(
            f"{path}: not a hunt table ({type(e).__name__}: {e}); choose another --out"
        ) from None
    if list(table.column_names) != list(COLUMNS):
        raise InputError(f"{path}: not a table of apf-viz hunt (other columns); choose another --out")
    return table.to_pylist()


def write_hunt(path: Path, rows: list[dict]) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    rows = sorted(rows, key=lambda r: tuple(str(r[c]) for c in KEY))
    schema = pa.schema(
        [
            (c, pa.int64() if c in INTEGERS else pa.float64() if c == "seconds" else pa.string())
            for c in COLUMNS
        ]
    )
    table = pa.Table.from_pylist(rows, schema=schema) if rows else schema.empty_table()
    replace_atomically(path, lambda tmp: pq.write_table(table, tmp))


def hunt_summary(rows: list[dict]) -> str:
    """Per algorithm and family: starts, verdicts, the largest k and the most states among them."""
    groups: dict[tuple[str, str], list[dict]] = {}
    for r in rows:
        groups.setdefault((r["algorithm"], r["family"]), []).append(r)
    lines = [
        "| algorithm | family | starts | k | verified | failures | budget | states (max) |",
        "|---|---|---:|---|---:|---|---:|---:|",
    ]
    for (alg, family), rs in sorted(groups.items()):
        verdicts: dict[str, int] = {}
        for r in rs:
            verdicts[r["verdict"]] = verdicts.get(r["verdict"], 0) + 1
        failures = ", ".join(
            f"{v} {n}" for v, n in sorted(verdicts.items()) if v not in ("verified", "budget")
        )
        ks = f"{min(r['k'] for r in rs)}–{max(r['k'] for r in rs)}"
        lines.append(
            f"| {alg} | {family} | {len(rs)} | {ks} | {verdicts.get('verified', 0)} | {failures or 'none'} "
            f"| {verdicts.get('budget', 0)} | {max(r['states'] for r in rs):,} |"
        )
    return "\n".join(lines)
