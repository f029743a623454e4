"""`apf-viz sweep`: thousands of runs on Dask, one results table.

The grid of runs is the product of the lists (k × seed × scheduler × algorithm × light semantics), or of
the start/pattern pairs of a folder instead of (k, seed). Each run is a task on a Dask cluster: by
default a ``LocalCluster`` of one single-threaded worker process per core; ``--cluster ADDRESS`` submits
to an existing scheduler. Results are one row per run (Parquet, or CSV by the file's extension), written
atomically as runs finish; re-running the same command skips the runs already in the file; Ctrl+C keeps
what finished. A run whose worker dies is recorded as ``error`` with the message, and the sweep goes on.

Reproducible starts (docs/SWEEPS.md): for (k, seed), the box is s × s with s = max(3, ⌊√(3k)⌋ + 1); the
robots are ``random_robots(k, s, s, 2·seed)`` (redrawn until solvable, as ``apf-viz random-robots``), the
pattern ``random_pattern(k, s, s, 2·seed + 1)``, the flips ``random_y_up(k, seed)``.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from apf_viz.core.formats import InputError, check_writable, replace_atomically, write_atomic

COLUMNS = (
    "k", "D", "seed", "scheduler", "algorithm", "light_semantics", "start", "outcome", "moves", "events",
    "cycles", "lights_used", "moves_per_kD", "wall_s", "trace", "error",
)  # fmt: skip
KEY = ("k", "seed", "scheduler", "algorithm", "light_semantics", "start")


@dataclass(frozen=True)
class Cell:
    """One run of the grid. ``start``: "" for a generated (k, seed) start, else the pair's name."""

    k: int
    seed: int
    scheduler: str
    algorithm: str
    light_semantics: str
    start: str = ""
    robots: tuple[tuple[int, int], ...] = ()
    pattern: tuple[tuple[int, int], ...] = ()
    y_up: tuple[bool, ...] = ()

    def key(self) -> tuple:
        return (self.k, self.seed, self.scheduler, self.algorithm, self.light_semantics, self.start)


def parse_range(text: str, what: str) -> list[int]:
    """ "1-50" or "5,10,20" (or both: "1-3,7") as integers; a reversed range is refused."""
    out: list[int] = []
    for part in text.split(","):
        part = part.strip()
        lo, dash, hi = part[1:].partition("-")  # a leading minus is a sign, not a range
        try:
            a, b = (int(part[0] + lo), int(hi)) if dash else (int(part), int(part))
        except (ValueError, IndexError):
            raise InputError(f"{what} {text!r}: not a list of integers or ranges like 1-50") from None
        if b < a:
            raise InputError(f"{what} {text!r}: the range {part} runs backwards")
        out.extend(range(a, b + 1))
    if not out:
        raise InputError(f"{what}: empty")
    return out


def generated_start(k: int, seed: int) -> tuple[list, list, list[bool]]:
    from apf_viz.core.frames import random_y_up
    from apf_viz.core.random_configs import random_pattern, random_robots

    side = max(3, math.isqrt(3 * k) + 1)
    return (
        random_robots(k, side, side, 2 * seed),
        random_pattern(k, side, side, 2 * seed + 1),
        list(random_y_up(k, seed)),
    )


def grid(
    ks: Sequence[int],
    seeds: Sequence[int],
    schedulers: Sequence[str],
    algorithms: Sequence[str],
    semantics: Sequence[str],
    starts: Path | None = None,
) -> list[Cell]:
    """The runs of the sweep; every name is checked first (one line for the first bad one)."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.schedulers import SCHEDULERS

    for name in algorithms:
        try:
            get_algorithm(name)
        except ValueError as e:
            raise InputError(f"--algorithms: {e}") from None
    for s in schedulers:
        if s not in SCHEDULERS or s == "manual":
            raise InputError(f"--schedulers: unknown scheduler {s!r}")
    for s in semantics:
        if s not in ("compute", "lc-atomic"):
            raise InputError(f"--light-semantics: {s!r} is not compute or lc-atomic")
    if starts is None and any(k < 1 for k in ks):
        raise InputError(f"--ks: a run needs at least one robot (got {min(ks)})")
    if any(seed < 0 for seed in seeds):
        raise InputError(f"--seeds: seeds are 0 or more (got {min(seeds)})")
    pairs: list[tuple[str, int, list, list, list[bool]]] = []
    if starts is not None:
        pairs = [(name, 0, r, p, f) for name, r, p, f in start_pairs(starts)]
    cells = []
    for sched in schedulers:
        for alg in algorithms:
            for sem in semantics:
                if starts is not None:
                    for name, _, r, p, f in pairs:
                        shape = (tuple(r), tuple(p), tuple(f))
                        cells += [Cell(len(r), seed, sched, alg, sem, name, *shape) for seed in seeds]
                else:
                    for k in ks:
                        for seed in seeds:
                            cells.append(Cell(k, seed, sched, alg, sem))
    return cells


def start_pairs(folder: Path) -> list[tuple[str, list, list, list[bool]]]:
    """``NAME.robots.json`` with ``NAME.pattern.json`` in ``folder`` (docs/SWEEPS.md)."""
    from apf_viz.core.formats import check_sizes, load_pattern, load_robots

    if not folder.is_dir():
        raise InputError(f"--starts {folder}: not a folder")
    pairs = []
    for robots_file in sorted(folder.glob("*.robots.json")):
        name = robots_file.name.removesuffix(".robots.json")
        pattern_file = folder / f"{name}.pattern.json"
        if not pattern_file.is_file():
            raise InputError(f"{robots_file}: no {pattern_file.name} beside it")
        robots, pattern = load_robots(robots_file), load_pattern(pattern_file)
        check_sizes(robots, pattern, str(pattern_file))
        points = [tuple(p) for p in robots.robots]
        pairs.append((name, points, [tuple(p) for p in pattern.points], robots.flips(1)))
    if not pairs:
        raise InputError(f"--starts {folder}: no NAME.robots.json / NAME.pattern.json pairs")
    return pairs


def run_cell(cell: Cell, traces: str | None = None) -> dict:
    """One run, on a worker: its row (a trace is written only for a run that did not form)."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.budget import paper_D, run_budget
    from apf_viz.core.engine import Engine
    from apf_viz.core.formats import trace_text, write_atomic
    from apf_viz.core.run import advance, trace_header
    from apf_viz.core.schedulers import make_scheduler

    if cell.robots:
        robots, pattern, y_up = list(cell.robots), list(cell.pattern), list(cell.y_up)
    else:
        robots, pattern, y_up = generated_start(cell.k, cell.seed)
    budget = run_budget(robots, pattern)
    t0 = time.perf_counter()
    engine = Engine(
        robots,
        pattern,
        get_algorithm(cell.algorithm),
        y_up=y_up,
        light_semantics=cell.light_semantics,  # type: ignore[arg-type]
        max_events=budget.max_events,
        max_moves=budget.max_moves,
    )
    advance(engine, make_scheduler(cell.scheduler), cell.seed)
    wall = time.perf_counter() - t0
    st = engine.state
    d = paper_D(robots, pattern)
    trace = ""
    if st.outcome != "formed" and traces:
        where = cell.start or f"k{cell.k}"
        name = f"{where}-s{cell.seed}-{cell.scheduler}-{cell.algorithm}-{cell.light_semantics}"
        path = Path(traces) / (name.replace("/", "_").replace("@", "_at_").replace(",", "+") + ".jsonl")
        header = trace_header(engine, cell.scheduler, cell.seed)
        write_atomic(path, trace_text(header, engine.history.events()))
        trace = str(path)
    outcome = st.outcome or "running"
    return row(cell, d, outcome, st.moves, st.events, st.cycles, len(st.lights_used), wall, trace)


def row(cell: Cell, d, outcome, moves, events, cycles, lights, wall, trace, error: str = "") -> dict:
    return {
        "k": cell.k, "D": d, "seed": cell.seed, "scheduler": cell.scheduler, "algorithm": cell.algorithm,
        "light_semantics": cell.light_semantics, "start": cell.start, "outcome": outcome, "moves": moves,
        "events": events, "cycles": cycles, "lights_used": lights,
        "moves_per_kD": (moves / (cell.k * d)) if d else 0.0, "wall_s": round(wall, 4), "trace": trace,
        "error": error,
    }  # fmt: skip


# ---------------------------------------------------------------------------------------------- results
def read_results(path: Path) -> list[dict]:
    if not path.exists():
        return []
    try:
        if path.suffix == ".csv":
            import csv

            with path.open(newline="") as f:
                return [_typed(r) for r in csv.DictReader(f)]
        import pyarrow.parquet as pq

        return pq.read_table(path).to_pylist()
    except Exception as e:  # a file that is not a results table: say so rather than overwrite it
        raise InputError(f"{path}: not a results table this sweep can resume ({e})") from None


def _typed(r: dict) -> dict:
    ints = ("k", "D", "seed", "moves", "events", "cycles", "lights_used")
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


# ---------------------------------------------------------------------------------------------- driving
def run_sweep(
    cells: Sequence[Cell],
    out: Path,
    *,
    traces: Path | None = None,
    workers: int | None = None,
    cluster: str | None = None,
    run: Callable[[Cell, str | None], dict] = run_cell,
    progress: Callable[[int, int, int, float], None] | None = None,
) -> list[dict]:
    """Run every cell not already in ``out`` on Dask; rows are written as they come (every few
    seconds) and at the end, also after Ctrl+C. Returns all rows of the file."""
    from dask.distributed import Client, LocalCluster, as_completed

    check_writable(out)
    if traces is not None:
        traces.mkdir(parents=True, exist_ok=True)
    rows = read_results(out)
    done = {tuple(r[c] for c in KEY) for r in rows}
    todo = [c for c in cells if c.key() not in done]
    if not todo:
        return rows
    local = None
    if cluster:
        client = Client(cluster, timeout="20s")
    else:
        local = LocalCluster(
            n_workers=workers or _cores(), threads_per_worker=1, processes=True, dashboard_address=None
        )
        client = Client(local)
    futures = {client.submit(run, c, str(traces) if traces else None, pure=False): c for c in todo}
    t0 = time.monotonic()
    finished = failed = 0
    last_write = t0
    try:
        for fut in as_completed(futures):
            cell = futures[fut]
            try:
                r = fut.result()
            except Exception as e:  # the run raised, or its worker died (KilledWorker)
                r = row(cell, 0, "error", 0, 0, 0, 0, 0.0, "", f"{type(e).__name__}: {e}"[:500])
            rows.append(r)
            finished += 1
            failed += r["outcome"] != "formed"
            if progress:
                progress(finished, len(todo), failed, time.monotonic() - t0)
            if time.monotonic() - last_write > 5:
                write_results(out, rows)
                last_write = time.monotonic()
    except KeyboardInterrupt:
        write_results(out, rows)  # first: every run that finished is kept, whatever shutting down does
        print("\napf-viz sweep: interrupted; keeping the runs that finished", file=sys.stderr)
        _shut_down(futures, client, local)
        raise
    write_results(out, rows)
    client.close()
    if local is not None:
        local.close()
    return rows


def _shut_down(futures, client, local) -> None:
    """Cancel what is queued and close the cluster; Dask may itself be interrupted mid-way (its errors
    then are its own, and the results are already written)."""
    try:
        client.cancel(list(futures))
        client.close()
        if local is not None:
            local.close()
    except BaseException:  # a second Ctrl+C, or Dask's own shutdown errors: nothing is lost
        pass


def _cores() -> int:
    import os

    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


def report_progress(finished: int, total: int, failed: int, seconds: float) -> None:
    eta = seconds / finished * (total - finished) if finished else 0.0
    print(
        f"\rapf-viz sweep: {finished}/{total} runs, {failed} not formed, {seconds:.0f} s, ETA {eta:.0f} s  ",
        end="" if finished < total else "\n",
        file=sys.stderr,
        flush=True,
    )


def summary(rows: Iterable[dict]) -> str:
    """Per algorithm × scheduler: runs, formed, failures by outcome, moves/(k·D) median and max."""
    import statistics

    groups: dict[tuple[str, str, str], list[dict]] = {}
    for r in rows:
        groups.setdefault((r["algorithm"], r["scheduler"], r["light_semantics"]), []).append(r)
    lines = ["| algorithm | scheduler | semantics | runs | formed | failures | moves/(k·D) median | max |",
             "|---|---|---|---:|---:|---|---:|---:|"]  # fmt: skip
    for (alg, sched, sem), rs in sorted(groups.items()):
        formed = [r for r in rs if r["outcome"] == "formed"]
        fails: dict[str, int] = {}
        for r in rs:
            if r["outcome"] != "formed":
                fails[r["outcome"]] = fails.get(r["outcome"], 0) + 1
        ratio = [r["moves_per_kD"] for r in formed]
        med = f"{statistics.median(ratio):.3f}" if ratio else "—"
        mx = f"{max(ratio):.3f}" if ratio else "—"
        failures = ", ".join(f"{k} {v}" for k, v in sorted(fails.items())) or "none"
        lines.append(f"| {alg} | {sched} | {sem} | {len(rs)} | {len(formed)} | {failures} | {med} | {mx} |")
    return "\n".join(lines)
