"""The lab's stages for one merge: stage 0, each start verified under the unmerged algorithm; stage 1,
the explorer over every schedule of the small starts; stage 2, random runs on larger starts."""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from pathlib import Path

from apf_viz.algorithms.merged_lights import AtWork, MergedLights
from apf_viz.core.files import write_atomic
from apf_viz.core.grid import Point, as_point
from apf_viz.lights.merges import (
    DEMO_SCALES,
    RANDOM_KS,
    RANDOM_SCHEDULERS,
    RANDOM_SYMMETRIC_KS,
    Merge,
    explore_every_flip,
    ks_label,
)


def verify_start(algorithm: str, name: str, start: list) -> dict:
    """On a worker: the base algorithm explored on one start under every flip assignment."""
    from apf_viz.algorithms import get_algorithm

    t0 = time.perf_counter()
    result, y_up = explore_every_flip(get_algorithm(algorithm), start)
    return {
        "start": name,
        "verdict": result.verdict,
        "detail": result.detail if result.verdict != "verified" else "",
        "y_up": list(y_up) if result.verdict != "verified" else [],
        "states": result.states,
        "seconds": round(time.perf_counter() - t0, 3),
    }


def explore_merge(merge: Merge, ks: Sequence[int], traces: str, starts: Sequence[tuple[str, list]]) -> dict:
    """On a worker: the explorer on every start (those the base algorithm verifies on) until the first
    violation; the merge's row."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.explore.check import counterexample_text
    from apf_viz.explore.small_starts import line_pattern

    algorithm = get_algorithm(merge.variant)
    assert isinstance(algorithm, MergedLights)
    counted = AtWork(algorithm)
    t0 = time.perf_counter()
    states = left_box = 0
    for n, (name, start) in enumerate(starts, 1):
        k = len(start)
        result, y_up = explore_every_flip(counted, start)
        states += result.states
        if result.verdict == "verified":
            continue
        base = {
            "k": k, "start": name, "y_up": json.dumps(list(y_up)), "starts": n, "states": states,
            "exercised": counted.count,
        }  # fmt: skip
        if result.verdict == "budget":
            return verdict_row(merge, ks, "inconclusive", "explorer", result.detail, t0=t0, **base)
        text = counterexample_text(algorithm, start, line_pattern(k), y_up, "async", result)
        violation = (
            result.detail
            if result.detail.startswith(result.verdict)
            else f"{result.verdict}: {result.detail}"
        )
        if result.verdict == "escape":
            evidence = _escape_shown(algorithm, text, result.detail)
            if evidence is None:  # it left the explored box, and every fair continuation ended: look on
                left_box += 1
                continue
            violation = f"{violation}; {evidence}"
        violation += f"; {_left(left_box)}" if left_box else ""
        path = Path(traces) / f"{merge.variant}.jsonl"
        write_atomic(path, text, through_links=False)
        return verdict_row(
            merge,
            ks,
            "breaks",
            "explorer",
            violation,
            events=text.count("\n") - 1,
            trace=str(path),
            t0=t0,
            **base,
        )
    verdict = "survives" if counted.count else "untested"
    return verdict_row(
        merge, ks, verdict, "explorer", _left(left_box), starts=len(starts), states=states,
        exercised=counted.count, t0=t0,
    )  # fmt: skip


def _left(starts: int) -> str:
    """The starts on which a robot left the explored box but every fair continuation ended."""
    if not starts:
        return ""
    return (
        f"on {starts} start{'s' if starts > 1 else ''} before, a robot left the explored box but every fair "
        "continuation ended (not an escape)"
    )


def _escape_shown(algorithm, text: str, detail: str) -> str | None:
    """How a fair continuation of the explorer's escape shows a walk without end, or None
    (:mod:`apf_viz.explore.escape`)."""
    from apf_viz.core.formats import parse_trace
    from apf_viz.explore.escape import escape_evidence, escaping_robot

    header, events = parse_trace(text)
    robot = escaping_robot(detail)
    evidence = escape_evidence(header, events, algorithm, robot)
    return None if evidence is None else evidence.describe(robot)


def verdict_row(merge: Merge, ks, verdict, stage, violation, *, t0: float, **values) -> dict:
    row = {
        "algorithm": merge.algorithm, "merge": merge.name, "shown": merge.shown, "hidden": merge.hidden,
        "ks": ks_label(ks), "verdict": verdict, "stage": stage, "violation": violation, "k": 0,
        "start": "", "y_up": "", "events": 0, "starts": 0, "states": 0, "random_runs": 0,
        "random_failed": 0, "seconds": round(time.perf_counter() - t0, 3), "trace": "", "error": "",
        "exercised": 0, "random_exercised": 0,
    }  # fmt: skip
    row.update(values)
    return row


MAX_RANDOM_RUNS = 10_000
"""Random runs per merge at most: every run is a task held in memory until the lab ends (10^12 of them
would never be made)."""


def random_cells(variants: Sequence[str], runs: int) -> list:
    """``runs`` random runs per variant (each merge the explorer could not break, and the base algorithm
    on the very same runs), the scheduler cycling through
    :data:`RANDOM_SCHEDULERS` and the start through three kinds in turn: a generated start (k = 6–12), a
    random symmetric start of 8–20 robots with robots on its axis (call, deciders and K at work, which
    random starts rarely reach), a Demo scenario's start scaled ×1, ×2 or ×3. The seed is the run's
    number; it draws the flips where the start gives none."""
    from apf_viz.core.adversarial_starts import symmetric_start
    from apf_viz.core.frames import random_y_up
    from apf_viz.sweeps import Cell

    demos = demo_starts()
    cells = []
    for variant in variants:
        for i in range(runs):
            seed, scheduler, n, kind = i + 1, RANDOM_SCHEDULERS[i % len(RANDOM_SCHEDULERS)], i // 3, i % 3
            if kind == 0 or not demos:
                cells.append(Cell(RANDOM_KS[n % len(RANDOM_KS)], seed, scheduler, variant, "compute"))
                continue
            robots: Sequence[Point]
            pattern: Sequence[Point]
            flips: Sequence[bool]
            if kind == 1:
                k = RANDOM_SYMMETRIC_KS[n % len(RANDOM_SYMMETRIC_KS)]
                robots, pattern, flips = symmetric_start(k, seed)
                name = f"symmetric k={k}"
            else:
                name, start, pattern, y_up = demos[n % len(demos)]
                scale = DEMO_SCALES[(n // len(demos)) % len(DEMO_SCALES)]
                robots = tuple((x * scale, y * scale) for x, y in start)
                name = f"{name} ×{scale}" if scale > 1 else name
                flips = tuple(y_up) if y_up is not None else tuple(random_y_up(len(robots), seed))
            shape = (tuple(map(as_point, robots)), tuple(map(as_point, pattern)), tuple(flips))
            cells.append(Cell(len(robots), seed, scheduler, variant, "compute", name, *shape))
    return cells


def demo_starts() -> list[tuple[str, tuple[Point, ...], tuple[Point, ...], list[bool] | None]]:
    """(name, robots, pattern, flips or None) of every Demo scenario with a solvable start."""
    from apf_viz.core.formats import load_pattern, load_robots
    from apf_viz.core.symmetry import unsolvable_axis
    from apf_viz.demos import scenarios

    out = []
    for scenario in scenarios().values():
        files = scenario.files()
        if "robots" not in files:
            continue
        robots = load_robots(files["robots"])
        points = tuple(as_point(p) for p in robots.robots)
        if unsolvable_axis(points) is None:
            pattern = tuple(as_point(p) for p in load_pattern(files["pattern"]).points)
            out.append((scenario.robots or "", points, pattern, robots.y_up))
    return out


def fold_random(row: dict, runs: Sequence[dict]) -> dict:
    """A row the explorer could not break, with its random runs counted: the first run that did not form
    breaks it; else it survives if its merge was ever at work, and is untested if never."""
    variant = Merge.of(row).variant
    mine = sorted((r for r in runs if r["algorithm"] == variant), key=lambda r: r["seed"])
    # A run fails the merge only where the base algorithm, on the same start, flips and schedule, forms:
    # elsewhere the failure is the base algorithm's own (and a run in which the merge never worked is
    # the base's run, event for event).
    base_formed = {
        _same_run(r) for r in runs if r["algorithm"] == row["algorithm"] and r["outcome"] == "formed"
    }
    failed = [
        r for r in mine if r["outcome"] != "formed" and r.get("hidden", 0) and _same_run(r) in base_formed
    ]
    at_work = sum(r.get("hidden", 0) for r in mine)
    row = dict(row, random_runs=len(mine), random_failed=len(failed), random_exercised=at_work)
    if row["verdict"] not in ("survives", "untested"):
        return row
    if not failed:
        row["verdict"] = "survives" if row["exercised"] or at_work else "untested"
    else:
        f = min(failed, key=lambda r: (r["events"], r["seed"]))  # the shortest to step through
        row.update(
            verdict="breaks",
            stage="random",
            violation=f"{f['outcome']}: {f['error']}".rstrip(": "),
            k=f["k"],
            start=f"{f['start'] or 'random k=' + str(f['k'])}, seed {f['seed']}, {f['scheduler']}",
            trace=f["trace"],
            events=f["events"],
        )
    return row


def _same_run(r: dict) -> tuple:
    return (r["k"], r["seed"], r["scheduler"], r["light_semantics"], r["start"])
