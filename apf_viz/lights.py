"""`apf-viz lights`: the light-budget lab. Which of an algorithm's lights could be one colour?

Every ordered pair (a, b) of the algorithm's lights names a variant ``ALG+merge(a=b)``: b is shown as a,
to every robot including itself (docs/ALGORITHM.md, "Variants"). Each merge is put to two tests:

1. **the explorer** (ASYNC, partial-order reduction): every solvable start of k ≤ 3 robots in a 4×4 box
   up to translation and mirror, then the stated k = 4–5 starts (:data:`STATED_STARTS`), each under every
   assignment of y-axis flips, towards a row of k points. The first violation ends the merge's search;
   its shortest schedule is kept as a trace.
2. **random adversarial runs** for the merges that survive: N runs, half of k = 6–12 random robots and
   half on the Demo scenarios' starts, under the async and stale-first schedulers, through the sweep
   machinery (``apf-viz sweep``'s Dask cluster, results file, resume and progress).

A merge that survives both has *evidence*, not a proof: small starts and random schedules.

One Dask task per merge. Rows are written atomically as merges finish; the same command resumes, skipping
the merges already in the file; Ctrl+C keeps what finished.
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from apf_viz.algorithms.merged_lights import MARKER, MergedLights, split_name
from apf_viz.core.formats import InputError, check_writable, replace_atomically, write_atomic
from apf_viz.progress import show_progress

COLUMNS = (
    "algorithm", "merge", "shown", "hidden", "ks", "verdict", "stage", "violation", "k", "start", "y_up",
    "events", "starts", "states", "random_runs", "random_failed", "seconds", "trace", "error",
)  # fmt: skip
KEY = ("algorithm", "merge", "ks")
RANDOM_KS = (6, 7, 8, 9, 10, 11, 12)
RANDOM_SCHEDULERS = ("async", "stale-first")
MAX_STATES = 2_000_000  # per start: a k = 5 start with every flip takes about 200,000 with the reduction


@dataclass(frozen=True)
class Merge:
    """One variant of the lab: ``hidden`` is shown as ``shown``."""

    algorithm: str
    shown: str
    hidden: str

    @property
    def name(self) -> str:
        return f"{self.shown}={self.hidden}"

    @property
    def variant(self) -> str:
        return f"{self.algorithm}{MARKER}{self.name})"

    @classmethod
    def of(cls, row: dict) -> Merge:
        return cls(row["algorithm"], row["shown"], row["hidden"])


def ks_label(ks: Sequence[int]) -> str:
    """The table's ``ks`` column: the explorer's robot counts, as "1,2,3"."""
    return ",".join(map(str, ks))


def merges(algorithm: str, only: str | None = None) -> list[Merge]:
    """Every ordered pair of the algorithm's lights, or the pairs ``only`` names ("a=b,c=d")."""
    from apf_viz.algorithms import get_algorithm

    try:
        lights = get_algorithm(algorithm).lights
    except ValueError as e:
        raise InputError(f"--algorithm: {e}") from None
    if MARKER in algorithm:
        raise InputError(
            f"--algorithm {algorithm}: the lab merges lights itself; name the algorithm unmerged"
        )
    every = [Merge(algorithm, a, b) for a in lights for b in lights if a != b]
    if only is None:
        return every
    chosen = []
    for part in only.split(","):
        a, eq, b = part.strip().partition("=")
        m = Merge(algorithm, a.strip(), b.strip())
        if not eq or m not in every:
            raise InputError(
                f"--merges {part.strip()!r}: not a=b with two different lights of {algorithm} "
                f"({', '.join(lights)})"
            )
        chosen.append(m)
    return chosen


def parse_ks(text: str) -> tuple[int, ...]:
    """The robot counts the explorer covers: 1–3 (every start of the box) and 4–5 (the stated starts)."""
    from apf_viz.sweep import parse_range

    ks = tuple(sorted(set(parse_range(text, "--ks"))))
    if not ks or ks[0] < 1 or ks[-1] > 5:
        raise InputError(
            f"--ks {text!r}: the explorer covers k = 1 to 5 (1–3: every start of a 4×4 box; 4–5: "
            "the stated starts)"
        )
    return ks


def starts_for(ks: Sequence[int]) -> list[tuple[str, list]]:
    """(name, start) in the order the explorer takes them: fewest robots first, so the first
    counterexample found is a small one."""
    from apf_viz.explore.small_starts import STATED_STARTS, solvable_box_starts

    out: list[tuple[str, list]] = []
    for k in ks:
        if k <= 3:
            out += [(json.dumps(s), s) for s in solvable_box_starts(k, 4, mirrored=True)]
        else:
            out += [(name, s) for name, s in STATED_STARTS.items() if len(s) == k]
    return out


# ---------------------------------------------------------------------------------------------- stage 1
def explore_merge(merge: Merge, ks: Sequence[int], traces: str) -> dict:
    """On a worker: the explorer on every start until the first violation; the merge's row."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.explore.check import all_flips, check, counterexample_text
    from apf_viz.explore.small_starts import line_pattern

    algorithm = get_algorithm(merge.variant)
    t0 = time.perf_counter()
    states = 0
    starts = starts_for(ks)
    for n, (name, start) in enumerate(starts, 1):
        k = len(start)
        result, y_up = check(algorithm, start, line_pattern(k), all_flips(k), "async", MAX_STATES, False)
        states += result.states
        if result.verdict == "verified":
            continue
        base = {"k": k, "start": name, "y_up": json.dumps(list(y_up)), "starts": n, "states": states}
        if result.verdict == "budget":
            return _row(merge, ks, "inconclusive", "explorer", result.detail, t0=t0, **base)
        text = counterexample_text(algorithm, start, line_pattern(k), y_up, "async", result)
        path = Path(traces) / f"{merge.variant}.jsonl"
        write_atomic(path, text)
        violation = (
            result.detail
            if result.detail.startswith(result.verdict)
            else f"{result.verdict}: {result.detail}"
        )
        return _row(
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
    return _row(merge, ks, "survives", "explorer", "", starts=len(starts), states=states, t0=t0)


def _row(merge: Merge, ks, verdict, stage, violation, *, t0: float, **values) -> dict:
    row = {
        "algorithm": merge.algorithm, "merge": merge.name, "shown": merge.shown, "hidden": merge.hidden,
        "ks": ks_label(ks), "verdict": verdict, "stage": stage, "violation": violation, "k": 0,
        "start": "", "y_up": "", "events": 0, "starts": 0, "states": 0, "random_runs": 0,
        "random_failed": 0, "seconds": round(time.perf_counter() - t0, 3), "trace": "", "error": "",
    }  # fmt: skip
    row.update(values)
    return row


# ---------------------------------------------------------------------------------------------- stage 2
MAX_RANDOM_RUNS = 10_000
"""Random runs per merge at most: every run is a task held in memory until the lab ends (10^12 of them
would never be made)."""


def random_cells(survivors: Sequence[Merge], runs: int) -> list:
    """``runs`` random runs per surviving merge, half on generated starts (k cycles through 6–12) and half
    on the Demo scenarios' starts (they reach what random starts rarely do: a symmetric start that needs
    call, deciders, robots on K); the scheduler alternates between async and stale-first, the seed is the
    run's number, and it draws the flips where the start file has none."""
    from apf_viz.core.frames import random_y_up
    from apf_viz.sweep import Cell

    demos = demo_starts()
    cells = []
    for m in survivors:
        for i in range(runs):
            seed, scheduler, n = i + 1, RANDOM_SCHEDULERS[(i // 2) % 2], i // 2
            if i % 2 == 0 or not demos:
                cells.append(Cell(RANDOM_KS[n % len(RANDOM_KS)], seed, scheduler, m.variant, "compute"))
                continue
            name, robots, pattern, y_up = demos[n % len(demos)]
            scheduler = RANDOM_SCHEDULERS[(n // len(demos)) % 2]  # each start under both, in turn
            flips = tuple(y_up) if y_up is not None else tuple(random_y_up(len(robots), seed))
            shape = (robots, pattern, flips)
            cells.append(Cell(len(robots), seed, scheduler, m.variant, "compute", name, *shape))
    return cells


def demo_starts() -> list[tuple[str, tuple, tuple, list[bool] | None]]:
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
        points = tuple(tuple(p) for p in robots.robots)
        if unsolvable_axis(points) is None:
            pattern = tuple(tuple(p) for p in load_pattern(files["pattern"]).points)
            out.append((scenario.robots, points, pattern, robots.y_up))
    return out


def fold_random(row: dict, runs: Sequence[dict]) -> dict:
    """A survivor's row with its random runs counted; the first run that did not form breaks it."""
    variant = Merge.of(row).variant
    mine = sorted((r for r in runs if r["algorithm"] == variant), key=lambda r: r["seed"])
    failed = [r for r in mine if r["outcome"] != "formed"]
    row = dict(row, random_runs=len(mine), random_failed=len(failed))
    if failed and row["verdict"] == "survives":
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


# ---------------------------------------------------------------------------------------------- driving
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
) -> list[dict]:
    """Both stages for every merge not already in ``out``; returns every row of the file."""
    from apf_viz import sweep

    check_writable(out)
    rows = read_lights(out)
    traces = traces or out.with_name(out.stem + "-traces")
    traces.mkdir(parents=True, exist_ok=True)
    ks_text = ks_label(ks)
    done = {tuple(r[c] for c in KEY) for r in rows}
    todo = [m for m in chosen if (m.algorithm, m.name, ks_text) not in done]
    if todo:
        rows += _explore_all(todo, ks, traces, out, rows, workers, cluster, progress)
    if random_runs:
        mine = {(m.algorithm, m.name) for m in chosen}
        survivors = [
            Merge.of(r)
            for r in rows
            if r["verdict"] == "survives" and r["ks"] == ks_text and (r["algorithm"], r["merge"]) in mine
        ]
        if survivors:
            runs = sweep.run_sweep(
                random_cells(survivors, random_runs),
                out.with_name(out.stem + "-random.parquet"),
                traces=traces,
                workers=workers,
                cluster=cluster,
                progress=sweep.report_progress if progress else None,
            )
            rows = [fold_random(r, runs) if r["ks"] == ks_text else r for r in rows]
            write_lights(out, rows)
    return rows


def _explore_all(todo, ks, traces, out, rows, workers, cluster, progress) -> list[dict]:
    from apf_viz.sweep import _client, _shut_down, by_the_second

    client, local = _client(cluster, workers)
    futures = {client.submit(explore_merge, m, tuple(ks), str(traces), pure=False): m for m in todo}
    new: list[dict] = []
    t0 = time.monotonic()
    try:
        for finished, _ in by_the_second(futures):
            for fut in finished:
                new.append(_result(fut, futures[fut], ks))
            if finished:
                write_lights(out, rows + new)
            if progress:
                progress(_progress_line(new, len(todo), time.monotonic() - t0))
    except KeyboardInterrupt:
        write_lights(out, rows + new)
        print("\napf-viz lights: interrupted; keeping the merges that finished", file=sys.stderr)
        _shut_down(futures, client, local)
        raise
    _shut_down(futures, client, local)
    return new


def _result(fut, merge: Merge, ks) -> dict:
    try:
        return fut.result()
    except Exception as e:  # the merge's search raised, or its worker died
        return _row(
            merge, ks, "error", "explorer", "", t0=time.perf_counter(), error=f"{type(e).__name__}: {e}"[:500]
        )


def _progress_line(new: list[dict], total: int, seconds: float) -> str:
    from apf_viz.sweep import _duration

    broken = sum(r["verdict"] == "breaks" for r in new)
    left = total - len(new)
    # Merges that break stop early and the rest run to the end: the average so far is a rough guide.
    eta = "done" if not left else _duration(seconds / len(new) * left) if new else "…"
    done = f"{len(new)}/{total} merges explored, {broken} broken"
    return f"apf-viz lights: {done}, {_duration(seconds)}, ETA {eta}"


def report_progress(line: str) -> None:
    show_progress(line, last=line.endswith("ETA done"))


# ---------------------------------------------------------------------------------------------- results
def read_lights(path: Path) -> list[dict]:
    """The rows of a lab's table, or [] when there is none; another file is refused, never overwritten."""
    if not path.exists():
        return []
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
        return tuple(pq.read_schema(path).names) == COLUMNS
    except Exception:
        return False


def write_lights(path: Path, rows: list[dict]) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    ints = ("k", "events", "starts", "states", "random_runs", "random_failed")
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
    for r in sorted(rows, key=lambda r: (r["verdict"] != "survives", r["shown"], r["hidden"])):
        if r["verdict"] == "survives":
            said = f"{r['starts']} starts, {r['states']:,} states"
            if r["random_runs"]:
                said += f", {r['random_runs']} random runs, all formed"
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


# ---------------------------------------------------------------------------------------------- stories
def story(trace: Path) -> str:
    """What a counterexample shows, in a sentence built from the trace itself: the first decision whose
    light the merge hides (and the rule that made it), then how the run ends."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.formats import load_trace
    from apf_viz.core.run import engine_for_trace, replay

    header, events = load_trace(trace)
    algorithm = get_algorithm(header.algorithm)
    engine = engine_for_trace(header, algorithm)
    replay(engine, events, str(trace))
    parts = split_name(header.algorithm)
    (shown, hidden), *_ = parts[1] if parts else [("?", "?")]
    at = next((n for n, ev in enumerate(events, 1) if ev.rule and " is shown as " in ev.rule), None)
    if (algorithm.base if isinstance(algorithm, MergedLights) else algorithm).lights[0] == hidden:
        first = f"every robot starts {hidden}, which shows {shown}"
    elif at is not None:
        ev = events[at - 1]
        first = f"at event {at} robot {ev.robot} turns {_meant(ev.rule)} ({ev.rule_id}) and shows {ev.light}"
    else:
        first = f"no robot shows {hidden} in these events"
    verdict = header.options.get("verdict", engine.outcome or "")
    return f"{first}; {_ending(verdict, header, events, engine)}"


def _meant(rule: str) -> str:
    """The light a merged decision's rule meant (the wrapper writes "(b is shown as a: merged)")."""
    return rule.rsplit(" (", 1)[1].split(" is shown as ")[0]


def _ending(verdict: str, header, events, engine) -> str:
    if verdict in ("deadlock", "stuck"):
        by_rule: dict[str, list[int]] = {}
        for r in range(engine.k):
            d = engine.decide(engine.look(r))
            meant = f" → {_meant(d.rule)}, shown as {d.light}" if " is shown as " in d.rule else ""
            by_rule.setdefault(f"{d.rule_id}{meant}", []).append(r)
        waits = "; ".join(f"{_robots(rs)} {rule}" for rule, rs in by_rule.items())
        return f"then nothing changes, not the pattern after {len(events)} events ({waits})"
    if verdict == "livelock":
        start = header.options.get("loop_starts_at_step", 0)
        loop = [ev.rule_id for ev in events[start:] if ev.phase == "compute" and ev.rule_id]
        return f"then a fair loop repeats forever ({', '.join(dict.fromkeys(loop)) or 'no decision'})"
    if verdict == "escape":
        robot = int(header.options["detail"].removeprefix("escape: robot ").split()[0])
        rules = [ev.rule_id for ev in events if ev.robot == robot and ev.phase == "compute" and ev.move]
        last = rules[-1] if rules else "?"
        return f"then robot {robot} walks away without end ({last}, {len(rules)} moves so far)"
    if verdict == "limit":
        return f"then it runs on until the event budget ({len(events)} events)"
    return f"then {header.options.get('detail', verdict)}"


def _robots(rs: list[int]) -> str:
    return f"robot {rs[0]}" if len(rs) == 1 else "robots " + ", ".join(map(str, rs))
