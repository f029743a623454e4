"""`apf-viz lights`: the light-budget lab. Which of an algorithm's lights could be one colour?

Every ordered pair (a, b) of the algorithm's lights names a variant ``ALG+merge(a=b)``: b is shown as a,
to every robot including itself (docs/ALGORITHM.md, "Variants"). Each merge is put to two tests:

0. **the base algorithm** is explored first on every start stage 1 uses: a start on which it fails
   itself cannot tell a merge's failure from its own, and is left out (and said).
1. **the explorer** (ASYNC, partial-order reduction): for each k, every start of k ≤ 5 robots in a 5×5
   box that is symmetric with robots on its axis (the hardest for leader election), then every solvable
   start of k ≤ 3 in a 4×4 box up to translation and mirror, then the stated k = 4–5 starts
   (:data:`STATED_STARTS`), each under every assignment of y-axis flips, towards a row of k points. The
   first violation ends the merge's search; its shortest schedule is kept as a trace.
2. **random adversarial runs** for the merges the explorer could not break: N runs under every scheduler
   (fsync, ssync, async, stale-first, round-robin), a third on random starts of k = 6–12, a third on
   random symmetric starts of 8–20 robots with robots on the axis, a third on the Demo scenarios' starts
   scaled ×1, ×2 and ×3, through the sweep machinery (``apf-viz sweep``'s Dask cluster, results file,
   resume and progress).

**Coverage before verdict.** A merge can only change a run where the base algorithm sets the hidden
light (it then shows the merged colour): the lab counts those decisions (``merged_lights.AtWork``) in
the explorer and in the random runs, each distinct view once per start (or per run), probes
included: a merge can turn a decision into "same light, stay", and then no Compute ever shows it. A
merge that breaks nowhere *and was never at work* is ``untested``, never ``survives``; one that was at
work and broke nowhere ``survives`` with its counts: evidence, not a proof.

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

from apf_viz.algorithms.merged_lights import MARKER, AtWork, MergedLights, split_name
from apf_viz.core.formats import InputError, check_writable, replace_atomically, write_atomic
from apf_viz.core.grid import Point, as_point
from apf_viz.core.schedulers import ordered
from apf_viz.progress import show_progress

COLUMNS = (
    "algorithm", "merge", "shown", "hidden", "ks", "verdict", "stage", "violation", "k", "start", "y_up",
    "events", "starts", "states", "random_runs", "random_failed", "seconds", "trace", "error",
    "exercised", "random_exercised",
)  # fmt: skip
# exercised: explorer views (each once per start) in which the base algorithm set the hidden light;
# random_exercised: the same in the random runs (decisions asked, each distinct view once per run).
KEY = ("algorithm", "merge", "ks")
RANDOM_KS = (6, 7, 8, 9, 10, 11, 12)
RANDOM_SCHEDULERS = ordered(
    ("fsync", "ssync", "async", "stale-first", "round-robin")
)  # numbered runs keep theirs
RANDOM_SYMMETRIC_KS = tuple(range(8, 21))
DEMO_SCALES = (1, 2, 3)
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
    counterexample found is a small one; for each k the symmetric starts with robots on the axis first
    (where leader election is hardest), each start once."""
    from apf_viz.core.pattern_match import normalise
    from apf_viz.explore.small_starts import STATED_STARTS, axis_symmetric_box_starts, solvable_box_starts

    out: list[tuple[str, list]] = []
    seen: set[tuple] = set()

    def add(name: str, start: list) -> None:
        key = tuple(normalise(start))
        if key not in seen:
            seen.add(key)
            out.append((name, start))

    for k in ks:
        for start in axis_symmetric_box_starts(k, 5) if k >= 2 else []:
            add(json.dumps(start), start)
        if k <= 3:
            for start in solvable_box_starts(k, 4, mirrored=True):
                add(json.dumps(start), start)
        else:
            for name, start in STATED_STARTS.items():
                if len(start) == k:
                    add(name, start)
    return out


def explore_every_flip(algorithm, start: list):
    """The explorer on one start towards a row of its robots, under every assignment of flips (ASYNC, the
    reduction): what stage 0 asks of the base algorithm and stage 1 of each merge."""
    from apf_viz.explore.check import all_flips, check
    from apf_viz.explore.small_starts import line_pattern

    k = len(start)
    return check(algorithm, start, line_pattern(k), all_flips(k), "async", MAX_STATES, False)


# ---------------------------------------------------------------------------------------------- stage 0
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


# ---------------------------------------------------------------------------------------------- stage 1
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
    states = 0
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
    verdict = "survives" if counted.count else "untested"
    return _row(
        merge, ks, verdict, "explorer", "", starts=len(starts), states=states, exercised=counted.count, t0=t0
    )


def _row(merge: Merge, ks, verdict, stage, violation, *, t0: float, **values) -> dict:
    row = {
        "algorithm": merge.algorithm, "merge": merge.name, "shown": merge.shown, "hidden": merge.hidden,
        "ks": ks_label(ks), "verdict": verdict, "stage": stage, "violation": violation, "k": 0,
        "start": "", "y_up": "", "events": 0, "starts": 0, "states": 0, "random_runs": 0,
        "random_failed": 0, "seconds": round(time.perf_counter() - t0, 3), "trace": "", "error": "",
        "exercised": 0, "random_exercised": 0,
    }  # fmt: skip
    row.update(values)
    return row


# ---------------------------------------------------------------------------------------------- stage 2
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
    from apf_viz.sweep import Cell

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
    """Every stage for every merge not already in ``out``; returns every row of the file."""
    from apf_viz import sweep

    check_writable(out)
    rows = read_lights(out)
    traces = traces or out.with_name(out.stem + "-traces")
    traces.mkdir(parents=True, exist_ok=True)
    ks_text = ks_label(ks)
    done = {tuple(r[c] for c in KEY) for r in rows}
    todo = [m for m in chosen if (m.algorithm, m.name, ks_text) not in done]
    if todo:
        starts = base_verified_starts(todo[0].algorithm, ks, base_path(out), workers, cluster, progress)
        rows += _explore_all(todo, ks, starts, traces, out, rows, workers, cluster, progress)
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
                out.with_name(out.stem + "-random.parquet"),
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


def base_path(out: Path) -> Path:
    """Where stage 0's verdicts on the base algorithm are kept beside the table (JSON)."""
    return out.with_name(out.stem + "-base.json")


def base_verified_starts(
    algorithm: str, ks: Sequence[int], path: Path, workers, cluster, progress
) -> list[tuple[str, list]]:
    """Stage 0: the base algorithm explored on every start of :func:`starts_for` (kept in ``path`` and
    reused when it covers them); the starts it verifies on, in order."""
    from apf_viz.sweep import _client, _shut_down, by_the_second

    starts = starts_for(ks)
    known: dict[str, dict] = {}
    if path.is_file():
        data = json.loads(path.read_text(encoding="utf-8"))
        if data.get("algorithm") == algorithm:
            known = {r["start"]: r for r in data["starts"]}
    todo = [(name, start) for name, start in starts if name not in known]
    if todo:
        client, local = _client(cluster, workers)
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
            write_atomic(path, _base_json(algorithm, known))
            _shut_down(futures, client, local)
    return [(name, start) for name, start in starts if known[name]["verdict"] == "verified"]


def _base_json(algorithm: str, known: dict[str, dict]) -> str:
    rows = sorted(known.values(), key=lambda r: r["start"])
    return json.dumps({"algorithm": algorithm, "starts": rows}, indent=1) + "\n"


def _explore_all(todo, ks, starts, traces, out, rows, workers, cluster, progress) -> list[dict]:
    from apf_viz.sweep import _client, _shut_down, by_the_second

    client, local = _client(cluster, workers)
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
        turns = _meant(ev.rule or "")
        first = f"at event {at} robot {ev.robot} turns {turns} ({ev.rule_id}) and shows {ev.light}"
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
