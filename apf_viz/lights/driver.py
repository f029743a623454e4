"""Driving the lab on Dask: every stage for every merge not already in the table, with progress and
Ctrl+C keeping what finished."""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from apf_viz.core.files import check_writable, make_folder, remove_if_empty, write_atomic
from apf_viz.lights.merges import KEY, Merge, ks_label, starts_for
from apf_viz.lights.stages import explore_merge, fold_random, random_cells, verdict_row, verify_start
from apf_viz.lights.table import read_lights, write_lights
from apf_viz.progress import show_progress


def run_lab(
    chosen: Sequence[Merge],
    ks: Sequence[int],
    out: Path,
    *,
    random_runs: int = 0,
    traces: Path | None = None,
    workers: int | None = None,
    cluster: str | None = None,
    progress: Callable[[str], None] | None = None,
    plan: str | None = None,
) -> list[dict]:
    """Every stage for every merge not already in ``out``; returns every row of the file. ``plan``: a
    line said once the inputs are checked and the cluster is reached, before any work (what the lab
    does and every file it writes)."""
    check_writable(out)
    for beside in (base_path(out), random_path(out)):  # files it names itself: checked before any work
        check_writable(beside, through_links=False)
    rows = read_lights(out)
    traces = traces or out.with_name(out.stem + "-traces")
    if plan is not None and cluster is not None:
        from apf_viz.sweeps import dask_client, shut_down

        client, local = dask_client(cluster, workers)  # an unreachable cluster: its one line, first
        shut_down({}, client, local)
    if plan is not None:
        print(plan, file=sys.stderr, flush=True)
    made = make_folder(traces)
    try:
        return _run_stages(chosen, ks, out, rows, traces, random_runs, workers, cluster, progress)
    except BaseException:
        remove_if_empty(made)  # a bad --cluster, Ctrl+C before any trace: no empty folder left
        raise


def _run_stages(
    chosen: Sequence[Merge],
    ks: Sequence[int],
    out: Path,
    rows: list[dict],
    traces: Path,
    random_runs: int,
    workers: int | None,
    cluster: str | None,
    progress: Callable[[str], None] | None,
) -> list[dict]:
    from apf_viz import sweeps as sweep

    ks_text = ks_label(ks)
    done = {tuple(r[c] for c in KEY) for r in rows}
    todo = [m for m in chosen if (m.algorithm, m.name, ks_text) not in done]
    if todo:
        starts = base_verified_starts(todo[0].algorithm, ks, base_path(out), workers, cluster, progress)
        bound = merges_bound(base_path(out), todo[0].algorithm, starts, len(todo), workers)
        if progress:
            print(
                f"apf-viz lights: {len(todo)} merges to explore on the {len(starts)} starts the base "
                f"algorithm verifies; at most about {sweep.duration(bound)} (stage 0's time on those "
                "starts for each merge, shared by the workers; a merge stops at its first failure)",
                file=sys.stderr,
                flush=True,
            )
        rows += _explore_all(todo, ks, starts, traces, out, rows, workers, cluster, progress, bound)
    if random_runs:
        mine = {(m.algorithm, m.name) for m in chosen}
        survivors = [
            Merge.of(r)
            for r in rows
            if r["verdict"] in ("survives", "untested")
            and r["ks"] == ks_text
            and (r["algorithm"], r["merge"]) in mine
        ]
        if survivors:
            variants = [survivors[0].algorithm] + [m.variant for m in survivors]
            runs = sweep.run_sweep(
                random_cells(variants, random_runs),
                random_path(out),
                traces=traces,
                workers=workers,
                cluster=cluster,
                progress=sweep.report_progress if progress else None,
            )
            rows = [
                fold_random(r, runs) if r["ks"] == ks_text and Merge.of(r) in survivors else r for r in rows
            ]
            write_lights(out, rows)
    return rows


def random_path(out: Path) -> Path:
    """Where the random runs' table is kept beside the table."""
    return out.with_name(out.stem + "-random.parquet")


def base_path(out: Path) -> Path:
    """Where stage 0's verdicts on the base algorithm are kept beside the table (JSON)."""
    return out.with_name(out.stem + "-base.json")


def base_verified_starts(
    algorithm: str, ks: Sequence[int], path: Path, workers, cluster, progress
) -> list[tuple[str, list]]:
    """Stage 0: the base algorithm explored on every start of :func:`starts_for` (kept in ``path`` and
    reused when it covers them); the starts it verifies on, in order."""
    from apf_viz.sweeps import by_the_second, dask_client, shut_down

    starts = starts_for(ks)
    known = kept_base(path, algorithm)
    todo = [(name, start) for name, start in starts if name not in known]
    if todo:
        client, local = dask_client(cluster, workers)
        futures = {
            client.submit(verify_start, algorithm, name, start, pure=False): name for name, start in todo
        }
        t0 = time.monotonic()
        try:
            for finished, _ in by_the_second(futures):
                for fut in finished:
                    r = fut.result()
                    known[r["start"]] = r
                if progress:
                    left = len(starts) - len(known)
                    progress(f"apf-viz lights: the base algorithm on {len(known)}/{len(starts)} starts, "
                             f"{time.monotonic() - t0:.0f} s{', ETA done' if not left else ''}")  # fmt: skip
        finally:
            write_atomic(path, _base_json(algorithm, known), through_links=False)
            shut_down(futures, client, local)
    return [(name, start) for name, start in starts if known[name]["verdict"] == "verified"]


def kept_base(path: Path, algorithm: str) -> dict[str, dict]:
    """Stage 0's rows kept in ``path`` by an earlier run for ``algorithm``, by start name (none if the
    file is missing or was made for another algorithm)."""
    if not path.is_file():
        return {}
    data = json.loads(path.read_text(encoding="utf-8"))
    return {r["start"]: r for r in data["starts"]} if data.get("algorithm") == algorithm else {}


def merges_bound(
    path: Path, algorithm: str, starts: Sequence[tuple[str, list]], merges: int, workers: int | None
) -> float:
    """About how long the merges can take at most, in seconds: each explores at most the starts the base
    algorithm verifies on, which stage 0 timed (kept in ``path``); the workers share them."""
    from apf_viz.sweeps import usable_cores

    timed = kept_base(path, algorithm)
    per_merge = sum(timed[name].get("seconds", 0.0) for name, _ in starts if name in timed)
    return merges * per_merge / (workers or usable_cores())


def _base_json(algorithm: str, known: dict[str, dict]) -> str:
    rows = sorted(known.values(), key=lambda r: r["start"])
    return json.dumps({"algorithm": algorithm, "starts": rows}, indent=1) + "\n"


def _explore_all(todo, ks, starts, traces, out, rows, workers, cluster, progress, bound: float) -> list[dict]:
    from apf_viz.sweeps import by_the_second, dask_client, shut_down

    client, local = dask_client(cluster, workers)
    shared = client.scatter(list(starts), broadcast=True)
    futures = {client.submit(explore_merge, m, tuple(ks), str(traces), shared, pure=False): m for m in todo}
    new: list[dict] = []
    t0 = time.monotonic()
    try:
        for finished, _ in by_the_second(futures):
            for fut in finished:
                new.append(_result(fut, futures[fut], ks))
            if finished:
                write_lights(out, rows + new)
            if progress:
                progress(_progress_line(new, len(todo), time.monotonic() - t0, bound))
    except KeyboardInterrupt:
        write_lights(out, rows + new)
        print("\napf-viz lights: interrupted; keeping the merges that finished", file=sys.stderr)
        shut_down(futures, client, local)
        raise
    shut_down(futures, client, local)
    return new


def _result(fut, merge: Merge, ks) -> dict:
    try:
        return fut.result()
    except Exception as e:  # the merge's search raised, or its worker died
        return verdict_row(
            merge, ks, "error", "explorer", "", t0=time.perf_counter(), error=f"{type(e).__name__}: {e}"[:500]
        )


def _progress_line(new: list[dict], total: int, seconds: float, bound: float) -> str:
    """Where the merges stand. The ETA counts down every second from the bound (stage 0's time per
    merge): merges that break stop early, so an average over the finished ones would promise too little
    and then stand still while the surviving ones run; past the bound it says by how much."""
    from apf_viz.sweeps import duration

    broken = sum(r["verdict"] == "breaks" for r in new)
    left = total - len(new)
    if not left:
        eta = "done"
    elif seconds <= bound:
        eta = f"at most about {duration(bound - seconds)}"
    else:
        eta = f"any moment (over the estimate by {duration(seconds - bound)})"
    done = f"{len(new)}/{total} merges explored, {broken} broken"
    return f"apf-viz lights: {done}, {duration(seconds)}, ETA {eta}"


def report_progress(line: str) -> None:
    show_progress(line, last=line.endswith("ETA done"))
