"""The lab's verdicts table (.parquet): read, written atomically, and summed up in words."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from apf_viz.core.files import check_readable, replace_atomically
from apf_viz.core.formats import InputError
from apf_viz.lights.merges import COLUMNS
from apf_viz.lights.stories import story


def read_lights(path: Path) -> list[dict]:
    """The rows of a lab's table, or [] when there is none; another file is refused, never overwritten."""
    if not path.exists():
        return []
    check_readable(path)  # a FIFO would block the reader
    try:
        import pyarrow.parquet as pq

        table = pq.read_table(path)
    except Exception as e:
        raise InputError(f"{path}: not a table apf-viz lights can resume ({type(e).__name__}: {e})") from None
    if tuple(table.column_names) != COLUMNS:
        raise InputError(f"{path}: not a table of apf-viz lights (other columns); choose another --out")
    return table.to_pylist()


def is_lights_table(path: Path) -> bool:
    import pyarrow.parquet as pq

    try:
        check_readable(path)
        return tuple(pq.read_schema(path).names) == COLUMNS
    except Exception:
        return False


def write_lights(path: Path, rows: list[dict]) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    ints = (
        "k",
        "events",
        "starts",
        "states",
        "random_runs",
        "random_failed",
        "exercised",
        "random_exercised",
    )
    schema = pa.schema(
        [(c, pa.int64() if c in ints else pa.float64() if c == "seconds" else pa.string()) for c in COLUMNS]
    )
    rows = sorted(rows, key=lambda r: (r["algorithm"], r["ks"], r["shown"], r["hidden"]))
    table = pa.Table.from_pylist(rows, schema=schema) if rows else schema.empty_table()
    replace_atomically(path, lambda tmp: pq.write_table(table, tmp))


def summary(rows: Sequence[dict]) -> str:
    """A Markdown table, a line per merge (survivors first), with what each counterexample shows; then
    the count of each verdict."""
    lines = [
        "| merge (b shown as a) | verdict | found by | violation | start, flips | evidence / what it shows |",
        "|---|---|---|---|---|---|",
    ]
    order = {"survives": 0, "untested": 1, "inconclusive": 2, "error": 3, "breaks": 4}
    for r in sorted(rows, key=lambda r: (order.get(r["verdict"], 5), r["shown"], r["hidden"])):
        if r["verdict"] in ("survives", "untested"):
            said = (
                f"{r['starts']} starts, {r['states']:,} states, the merge at work in {r['exercised']:,} views"
            )
            if r["random_runs"]:
                failed = (
                    f"{r['random_failed']} failed where the base formed"
                    if r["random_failed"]
                    else "none failed"
                )
                said += (
                    f"; {r['random_runs']} random runs, the merge at work in {r['random_exercised']:,} "
                    f"decisions, {failed}"
                )
        elif r["trace"] and Path(r["trace"]).is_file():
            said = story(Path(r["trace"]))
        else:
            said = r["error"] or "(no trace)"
        where = f"{r['start']} {r['y_up']}".strip()
        lines.append(
            f"| {r['shown']}={r['hidden']} | {r['verdict']} | {r['stage']} | {r['violation'].split(':')[0]} "
            f"| {where} | {said} |"
        )
    counts: dict[str, int] = {}
    for r in rows:
        counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
    lines.append("")
    lines.append(", ".join(f"{v} {n}" for v, n in sorted(counts.items())))
    return "\n".join(lines)
