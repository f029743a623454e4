"""The grid of runs: each run (a :class:`Cell`) from its lists, its start (generated or a named pair), and
running one to its row of results."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from apf_viz.algorithms.merged_lights import AtWork, MergedLights
from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError
from apf_viz.core.grid import as_point

COLUMNS = (
    "k", "D", "seed", "scheduler", "algorithm", "light_semantics", "start", "outcome", "moves", "events",
    "cycles", "lights_used", "moves_per_kD", "wall_s", "trace", "error", "hidden",
)  # fmt: skip
# Added later: a table written before it still resumes (read as 0).
_LATER_COLUMNS = {"hidden": 0}
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
    timeout: float | None = None  # seconds; a run past it is recorded as "timeout" (not part of the key)
    # WORST_FOUND's: the schedules its search tries beside the built-ins' 100 runs (beams of width 64,
    # 128, 256 and 512; not part of the key; docs/SWEEPS.md)
    search_budget: int = 4

    def key(self) -> tuple:
        return (self.k, self.seed, self.scheduler, self.algorithm, self.light_semantics, self.start)


WORST_FOUND = "worst-found"
"""A "scheduler" of the sweep that is none: the searched adversary (``apf-viz adversary``, moves), its
costliest schedule found at the sweep's ``--search-budget`` the run of the row."""
MAX_VALUES = 100_000  # values one --ks or --seeds list may name
MAX_RUNS = 1_000_000  # runs one sweep may hold (its rows are kept in memory)
MAX_K = 100_000  # robots per generated start (random_configs.MAX_RANDOM_POINTS)


def parse_range(text: str, what: str) -> list[int]:
    """ "1-50" or "5,10,20" (or both: "1-3,7") as integers; a reversed range is refused, and so is a
    list of more than :data:`MAX_VALUES` values, counted before any is made."""
    parts: list[tuple[int, int]] = []
    for part in text.split(","):
        part = part.strip()
        lo, dash, hi = part[1:].partition("-")  # a leading minus is a sign, not a range
        try:
            a, b = (int(part[0] + lo), int(hi)) if dash else (int(part), int(part))
        except (ValueError, IndexError):
            raise InputError(f"{what} {text!r}: not a list of integers or ranges like 1-50") from None
        if b < a:
            raise InputError(f"{what} {text!r}: the range {part} runs backwards")
        parts.append((a, b))
    count = sum(b - a + 1 for a, b in parts)
    if count > MAX_VALUES:
        raise InputError(f"{what} {text!r}: {count:,} values, more than the {MAX_VALUES:,} a sweep takes")
    return [v for a, b in parts for v in range(a, b + 1)]


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
    from apf_viz.core.schedulers import AUTOMATIC

    for name in algorithms:
        try:
            get_algorithm(name)
        except ValueError as e:
            raise InputError(f"--algorithms: {e}") from None
    choices = (*AUTOMATIC, WORST_FOUND)
    for s in schedulers:
        if s not in choices:
            raise InputError(f"--schedulers: unknown scheduler {s!r} (choose from {', '.join(choices)})")
    for s in semantics:
        if s not in ("compute", "lc-atomic"):
            raise InputError(
                f"--light-semantics: {s!r} is not compute or lc-atomic (choose from compute, lc-atomic)"
            )
    if starts is None and any(k < 1 for k in ks):
        raise InputError(f"--ks: a run needs at least one robot (got {min(ks)})")
    if starts is None and any(k > MAX_K for k in ks):
        raise InputError(f"--ks: at most {MAX_K:,} robots per run (got {max(ks):,})")
    if any(seed < 0 for seed in seeds):
        raise InputError(f"--seeds: seeds are 0 or more (got {min(seeds)})")
    pairs: list[tuple[str, int, list, list, list[bool]]] = []
    if starts is not None:
        pairs = [(name, 0, r, p, f) for name, r, p, f in start_pairs(starts)]
    runs = len(pairs or ks) * len(seeds) * len(schedulers) * len(algorithms) * len(semantics)
    if runs > MAX_RUNS:
        raise InputError(f"the sweep has {runs:,} runs, more than the {MAX_RUNS:,} one sweep takes; split it")
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
        points = [as_point(p) for p in robots.robots]
        pairs.append((name, points, [as_point(p) for p in pattern.points], robots.flips(1)))
    if not pairs:
        raise InputError(f"--starts {folder}: no NAME.robots.json / NAME.pattern.json pairs")
    return pairs


def run_cell(cell: Cell, traces: str | None = None) -> dict:
    """One run, on a worker: its row (a trace is written only for a run that did not form)."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.budget import paper_D, run_budget
    from apf_viz.core.engine import Engine
    from apf_viz.core.formats import trace_text
    from apf_viz.core.run import advance, trace_header
    from apf_viz.core.schedulers import make_scheduler

    if cell.robots:
        robots, pattern, y_up = list(cell.robots), list(cell.pattern), list(cell.y_up)
    else:
        robots, pattern, y_up = generated_start(cell.k, cell.seed)
    if cell.scheduler == WORST_FOUND:
        return _worst_found(cell, robots, pattern, y_up)
    budget = run_budget(robots, pattern)
    t0 = time.perf_counter()
    algorithm = get_algorithm(cell.algorithm)
    if isinstance(algorithm, MergedLights):
        algorithm = AtWork(algorithm)  # counts the decisions its merge is at work in (the light lab)
    engine = Engine(
        robots,
        pattern,
        algorithm,
        y_up=y_up,
        light_semantics=cell.light_semantics,  # type: ignore[arg-type]
        max_events=budget.max_events,
        max_moves=budget.max_moves,
        fast_forward=True,
    )
    scheduler = make_scheduler(cell.scheduler)
    if cell.timeout is None:
        advance(engine, scheduler, cell.seed)
    else:
        deadline = t0 + cell.timeout
        while not engine.finished and time.perf_counter() < deadline:
            advance(engine, scheduler, cell.seed, steps=_TIMEOUT_CHUNK)
    wall = time.perf_counter() - t0
    st = engine.state
    d = paper_D(robots, pattern)
    trace = ""
    if st.outcome != "formed" and traces:
        where = cell.start or f"k{cell.k}"
        name = f"{where}-s{cell.seed}-{cell.scheduler}-{cell.algorithm}-{cell.light_semantics}"
        path = Path(traces) / (name.replace("/", "_").replace("@", "_at_").replace(",", "+") + ".jsonl")
        header = trace_header(engine, cell.scheduler, cell.seed)
        write_atomic(path, trace_text(header, engine.history.events()), through_links=False)
        trace = str(path)
    outcome = st.outcome or "timeout"
    hidden = algorithm.count if isinstance(algorithm, AtWork) else 0
    return row(
        cell, d, outcome, st.moves, st.events, st.cycles, len(st.lights_used), wall, trace, hidden=hidden
    )


def _worst_found(cell: Cell, robots: list, pattern: list, y_up: list) -> dict:
    """The searched adversary's row: the costliest schedule in moves it found (explore/adversary.py),
    run in the engine again for its counts. No timeout: the search's budget bounds it."""
    from apf_viz.core.budget import paper_D
    from apf_viz.explore.adversary import Problem, search

    t0 = time.perf_counter()
    problem = Problem(
        cell.algorithm, tuple(map(tuple, robots)), tuple(map(tuple, pattern)), tuple(y_up), "moves",
        cell.light_semantics,  # type: ignore[arg-type]
    )  # fmt: skip
    found = search(problem, cell.search_budget, seed=cell.seed)
    st = problem.replayed(found.best.records).state
    d = paper_D(robots, pattern)
    wall = time.perf_counter() - t0
    return row(
        cell, d, st.outcome or "timeout", st.moves, st.events, st.cycles, len(st.lights_used), wall, ""
    )


_TIMEOUT_CHUNK = 2_000  # steps between looks at the clock: milliseconds at any k


def row(
    cell: Cell, d, outcome, moves, events, cycles, lights, wall, trace, error: str = "", hidden: int = 0
) -> dict:
    return {
        "k": cell.k, "D": d, "seed": cell.seed, "scheduler": cell.scheduler, "algorithm": cell.algorithm,
        "light_semantics": cell.light_semantics, "start": cell.start, "outcome": outcome, "moves": moves,
        "events": events, "cycles": cycles, "lights_used": lights,
        "moves_per_kD": (moves / (cell.k * d)) if d else 0.0, "wall_s": round(wall, 4), "trace": trace,
        "error": error, "hidden": hidden,
    }  # fmt: skip
