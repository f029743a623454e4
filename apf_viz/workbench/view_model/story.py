"""The story of a run in words: what just happened (events), how it ended (banners, a collision located),
where the run stands (stats, a followed trace, Compare, Manual's next phases) and what the selected robot
holds (the caption). Every sentence the panels show about the run is made here, from engine state."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from apf_viz.core.engine import Engine
from apf_viz.core.engine_state import Phase
from apf_viz.core.grid import Direction, Point, as_point
from apf_viz.core.history import Event
from apf_viz.core.schedulers import SYNCHRONOUS
from apf_viz.workbench.compare import Divergence
from apf_viz.workbench.view_model.legend import symbol_html
from apf_viz.workbench.view_model.staleness import SeenRobot, changes

MAX_DIFFS = 8  # snapshot differences listed in the caption (the rest are counted)
# Symbols, not emoji: a fresh machine's browser may have no colour-emoji font (Debian's Chromium with
# only DejaVu drew the banner's emoji as empty boxes); these four are in DejaVu Sans, as ↻ is.
OUTCOME_ICONS = {"formed": "✔", "collision": "✖", "stuck": "⊘", "limit": "◷"}


_FLIPPED = {"up": "down", "down": "up", "left": "left", "right": "right"}


def describe_event(ev: Event, stays: bool = False, was: str | None = None, y_up: bool = True) -> str:
    """One event in words: "robot 3 · Move → (1, 0) on the grid",
    "robot 1 · Compute: off → leader1, stay — A1.off.on-K"
    (``stays``: the Move of a decision to stay; ``was``: the light before a Compute, when known;
    ``y_up``: the robot's flip, to say a vertical move in its own frame as well as on screen)."""
    head = f"robot {ev.robot} · "
    if ev.phase == "look":
        return head + f"Look: sees {len(ev.sees or ())} robots"
    if ev.phase == "compute":
        rule = f" — {ev.rule_id or ev.rule}" if (ev.rule_id or ev.rule) else ""
        if was is None:
            light = f"light {ev.light}"
        else:
            light = f"{was} → {ev.light}" if was != ev.light else f"stays {ev.light}"
        return head + f"Compute: {light}, {move_words(ev.move, y_up)}{rule}"
    # The screen's coordinates, said so: a lecture's words give the leader's frame, Why a robot's own.
    assert ev.to is not None  # a Move event says where it ended
    x, y = ev.to
    if ev.collision:
        return head + f"Move → ({x}, {y}) on the grid: COLLISION"
    if stays:
        return head + f"Move: stays at ({x}, {y}) on the grid"
    return head + f"Move → ({x}, {y}) on the grid"


def move_words(move: Direction | None, y_up: bool) -> str:
    """A decided move (global frame) as the robot meant it and as the screen shows it: "move left",
    "move up (its own frame; down on screen)" for a robot whose y-axis the adversary flipped."""
    if move is None:
        return "stay"
    on_screen = move.value
    own = on_screen if y_up else _FLIPPED[on_screen]
    return f"move {own}" if own == on_screen else f"move {own} (its own frame; {on_screen} on screen)"


def last_events(e: Engine, n: int = 8) -> tuple[str, ...]:
    """The last ``n`` events, newest first, in words: who did what. A robot's newest Compute says the
    light it left: the light it held at the Look it decided on (only its own Compute sets its light)."""
    st = e.state
    out: list[str] = []
    window = e.history.steps[max(0, e.step_index - n) : e.step_index]
    latest_seen: set[int] = set()
    computed: set[int] = set()  # robots whose newest Compute is already described
    for step in reversed(window):
        for ev in reversed(step.events):
            stays, was = False, None
            r = ev.robot
            decided = st.decided[r]
            if ev.phase == "move" and r not in latest_seen and decided is not None:
                # Its latest event: the decision it moved on is the one on its latest decided snapshot.
                stays = e.decide(decided).move is None
            if ev.phase == "compute":
                if r not in computed and decided is not None:
                    was = decided.light
                computed.add(r)
            latest_seen.add(r)
            out.append(describe_event(ev, stays, was, bool(e.y_up[r])))
            if len(out) == n:
                return tuple(out)
    return tuple(out)


MAX_TRAIL = 50  # moves per robot a trail can show
LOOP_TRAIL = 24  # a livelock's or an escape's trace shows this many moves of each walker anyway
# A trail reads the history backwards from now; it stops after this many steps whatever it found (a
# robot that has not moved for a long time has a short trail rather than costing a frame).
TRAIL_STEPS = 20_000


def trails(e: Engine, moves: int, now: Sequence[Point]) -> tuple[tuple[Point, ...], ...]:
    """Each robot's path over its last ``moves`` moves, oldest first, ending where it stands; a robot
    that has not moved has an empty path. Read backwards from now: each Move lands where the robot stood
    until its next one, so the distinct landings, newest first, are the path reversed."""
    if moves <= 0:
        return ()
    paths: list[list[Point]] = [[as_point(p)] for p in now]
    open_ = set(range(e.k))
    steps = e.history.steps
    first = max(0, e.step_index - TRAIL_STEPS)
    for i in range(e.step_index - 1, first - 1, -1):
        for ev in reversed(steps[i].events):
            if ev.phase == "move" and not ev.collision and ev.robot in open_ and ev.to is not None:
                path = paths[ev.robot]
                if ev.to != path[-1]:
                    path.append(ev.to)
                    if len(path) > moves:
                        open_.discard(ev.robot)
        if not open_:
            break
    if first == 0:  # the whole history was read: the robots still open began at their start
        for r in open_:
            if tuple(e.start[r]) != paths[r][-1]:
                paths[r].append(tuple(e.start[r]))  # type: ignore[arg-type]
    return tuple(tuple(reversed(p)) if len(p) > 1 else () for p in paths)


LAST_DECISION_STEPS = 200  # how far back the Paper panel looks for the run's last Compute


def last_decision(e: Engine) -> tuple[int, str] | None:
    """(robot, rule id) of the run's latest Compute within the last LAST_DECISION_STEPS steps."""
    steps = e.history.steps
    for i in range(e.step_index - 1, max(-1, e.step_index - 1 - LAST_DECISION_STEPS), -1):
        for ev in reversed(steps[i].events):
            if ev.phase == "compute" and ev.rule_id:
                return ev.robot, ev.rule_id
    return None


def last_actor(e: Engine) -> int | None:
    """The robot of the last step when one robot alone took it (ASYNC, Manual), else None (at the start, or a
    round)."""
    if e.step_index == 0:
        return None
    events = e.history.steps[e.step_index - 1].events
    return events[-1].robot if len(events) == 1 else None


def collision(e: Engine, pts: list[Point]) -> tuple[str, tuple[Point, ...], tuple[int, ...]] | None:
    """The colliding moves of the last step: in words, the cells they collide in (each move's landing:
    the moves are not applied, so each mover still stands on its own cell, its move drawn into the
    burst) and the robots involved."""
    if e.step_index == 0:
        return None
    st = e.state
    movers = [ev for ev in e.history.steps[e.step_index - 1].events if ev.collision and ev.to is not None]
    where = {p: i for i, p in enumerate(pts)}
    words: list[str] = []
    cells: list[Point] = []
    robots: list[int] = []
    for ev in movers:
        assert ev.to is not None  # a move's landing
        other = where.get(ev.to)
        onto = f"onto robot {other}" if other is not None and other != ev.robot else "into another mover"
        words.append(
            f"robot {ev.robot} moved {onto} at ({ev.to[0]}, {ev.to[1]}) on a snapshot taken at step "
            f"{int(st.look_step[ev.robot])}"
        )
        cells.append(ev.to)  # where it happens; the mover stands on its cell, its move drawn into this one
        robots += [ev.robot] + ([other] if other is not None and other != ev.robot else [])
    if not words:
        return None
    return "; ".join(words), tuple(dict.fromkeys(cells)), tuple(dict.fromkeys(robots))


def fatal_decisions(e: Engine, robots: tuple[int, ...], now: list[Point]) -> tuple[str, int | None]:
    """Why a collision happened, robot by robot: the step at which each mover decided its move (its
    Compute), the step of the Look it decided on, and what has changed since in what it saw (the
    staleness of that snapshot); and the step of the earliest such Compute (to jump to), if any."""
    st = e.state
    steps = e.history.steps
    lines, first = [], None
    for r in robots:
        if st.phase[r] != Phase.COMPUTED or st.snapshot[r] is None:  # a robot holding its fatal decision
            continue
        computed = next(
            (
                i + 1
                for i in range(e.step_index - 1, -1, -1)
                for ev in steps[i].events
                if ev.robot == r and ev.phase == "compute"
            ),
            None,
        )
        since = changes(e, r, "held", now)
        what = "; ".join(c.describe() for c in since) or "nothing it saw has changed"
        lines.append(
            f"robot {r} decided this move at step {computed} on what it saw at step {int(st.look_step[r])}; "
            f"since then: {what}"
        )
        if computed is not None:
            first = computed if first is None else min(first, computed)
    return "  \n".join(lines), first


WAIT_FOR_UP_TO = 200  # robots: a deadlock's wait-for summary asks each robot once (a thousand cost a frame)


def wait_for(e: Engine) -> str:
    """A deadlock's wait-for summary: what each robot would decide now (its rule: what it waits on),
    robots grouped by rule."""
    if e.k > WAIT_FOR_UP_TO:
        return ""
    groups: dict[str, list[int]] = {}
    for r in range(e.k):
        d = e.decide(e.look(r))
        groups.setdefault(f"{d.rule_id or '—'}: {d.rule}" if d.rule else (d.rule_id or "stay"), []).append(r)
    return "  \n".join(
        f"robot{'s' if len(rs) > 1 else ''} {', '.join(map(str, rs))} — {why}" for why, rs in groups.items()
    )


ENDLESS = ("livelock", "escape")  # a checker's verdicts on runs that never end


def endless_words(options: Mapping[str, object]) -> tuple[str, str]:
    """A livelock's or an escape's trace at its end: (its verdict as a heading, in words) — the run has
    not ended, and never would."""
    problems = options.get("problems")
    where = f" ({problems[0]})" if isinstance(problems, list) and problems else ""
    if options.get("verdict") == "escape":
        return "ESCAPE", (
            f"The robots walk away for ever{where}: the checker stops where a robot leaves the box around "
            "the start and the pattern, and the adversary can repeat the same cycles without end. The "
            "trails show the walk."
        )
    return "LIVELOCK", (
        f"The same configurations come back for ever{where}: the loop marked on the timeline repeats "
        "without end under this adversary. The trails show the loop."
    )


def banner(
    outcome: str | None,
    collision_words: str | None,
    stuck: bool,
    why: str = "",
    endless: tuple[str, str] | None = None,
    mirrored: bool = False,
) -> str:
    """The outcome as a heading, and where it happened; ``endless``: a livelock's or an escape's trace
    played to its end (the engine sees a run still going); ``mirrored``: formed as the pattern's mirror
    image in y."""
    if outcome is None:
        if endless is not None:
            verdict, words = endless
            return f"## ↻ {verdict}: it never ends\n\n{words}"
        return ""
    detail = f"\n\n{collision_words} (the magenta burst on the grid)" if collision_words else ""
    if stuck:
        detail = "\n\nNo next cycle of any robot changes anything: all (each in a grey square) will never act"
    if outcome == "formed":
        detail = "\n\nEvery robot is on a target cell of the pattern."
        if mirrored:
            detail += (
                " The shape is the drawn pattern upside down: the robots agree only on which way is "
                "right, not on which way is up, so a pattern and its mirror image top to bottom are the "
                "same pattern to them (the leader's y-axis chose)."
            )
    if why:
        detail += f"\n\n**{'Waiting' if stuck else 'Why'}:**  \n{why}"
    return f"## {OUTCOME_ICONS.get(outcome, '')} {outcome.upper()}{detail}"


def stats(algorithm: str, numbers: Mapping[str, object]) -> str:
    """The Stats panel's text (Markdown): the algorithm, moves, cycles, step, stage, moves/(k·D), robot·steps
    passed over and the lights in use."""
    n = numbers
    skipped = n["skipped"]
    return (
        f"Algorithm **{algorithm}**  \n"
        f"Moves **{n['moves']}** · cycles **{n['cycles']}** · step {n['steps']}/{n['history_length']}  \n"
        f"Stage: **{n['stage']}** · moves/(k·D) = {n['moves_per_kD']:.3f}  \n"
        + (f"Passed over (changing nothing): {skipped:,} robot·steps  \n" if skipped else "")
        + f"Lights in use: {', '.join(n['lights_in_use'])}"  # type: ignore[arg-type]
    )


def trace_note(options: Mapping[str, object]) -> str:
    """What a trace's header says it shows, in one line ("" for a plain recorded run)."""
    verdict = options.get("verdict") or options.get("literal_failure")
    detail = options.get("detail")
    problems = options.get("problems")
    if not detail and isinstance(problems, list) and problems:
        detail = str(problems[0])
    gap = options.get("shows_gap")
    parts = [str(options["found"])] if options.get("found") else []
    if gap:
        parts.append(f"shows gap {gap} (the variant without its resolution)")
    if verdict:
        detail = str(detail or "").removeprefix(f"{verdict}: ")
        parts.append(f"verdict: {verdict}" + (f" — {detail}" if detail and detail != verdict else ""))
    return "; ".join(parts)


def trace_line(position: tuple[int, int] | None, what: str, note: str) -> str:
    """Following a trace or schedule: where in it, and what its header says it shows."""
    line = ""
    if position is not None:
        at, of = position
        end = " — its end" if at >= of else ""
        line = f"Following {what}: event **{at}** of {of}{end}"
    if note:
        line += f"  \n<small>The trace: {symbol_html(note)}</small>"
    return line


def aside_line(branches: tuple[str, ...]) -> str:
    """The branches kept, each re-enterable from the Branches list."""
    if not branches:
        return ""
    return f"Branches kept: **{len(branches)}** (Enter branch follows one; the line you leave is kept)."


def loop_marks(options: Mapping[str, object], steps: int, scheduler: str) -> tuple[tuple[int, str], ...]:
    """A livelock from ``apf-viz check``: the header gives the explorer step where the loop begins, and
    the trace runs the loop twice; marks where it begins, repeats and ends, in engine steps (a
    synchronous explorer step is three engine steps: Looks, Computes, Moves)."""
    start = options.get("loop_starts_at_step")
    if not isinstance(start, int) or isinstance(start, bool) or start < 0:
        return ()
    per = 3 if scheduler in SYNCHRONOUS else 1
    items = steps // per
    if items <= start:
        return ()
    twice = (items - start) // 2
    first, again = start * per, (start + twice) * per
    return ((first, "loop starts"), (again, "loop repeats"), (again + twice * per, "…for ever"))


def compare_text(
    a: tuple[str, str | None, int, int], b: tuple[str, str | None, int, int], divergence: Divergence | None
) -> str:
    """Compare: each side's (algorithm, outcome, event, moves), the first decision where they differ and the
    move that follows it in each."""

    def side(name: str, s: tuple[str, str | None, int, int]) -> str:
        algorithm, outcome, event, moves = s
        return f"{name} **{algorithm}**: {(outcome or 'running').upper()}, event {event}, {moves} moves"

    if divergence is None:
        split = "Same decisions so far."
    else:
        at, what, robot, then = divergence
        a_did, b_did = what.split(" | ")
        split = f"First differing decision at event **{at}**, robot {robot} (◆): A {a_did}; B {b_did}"
        if then:
            a_then, b_then = then.split(" | ")
            split += f"  \nIts consequence: A {a_then}; B {b_then}"
    return f"{side('A', a)}  \n{side('B', b)}  \n{split}"


def counts(mode: str, draft_count: int, robot_count: int, robots: int, axis: float | None) -> str:
    """The Edit folder's line: the draft's size against the other draft's, and (robots) Theorem 1."""
    if mode == "edit-pattern":
        fit = "" if draft_count == robot_count else " — Fit pattern or Fit robots makes them equal"
        return f"Targets: **{draft_count}** / robots: {robot_count}{fit}"
    if mode == "edit-robots":
        if robot_count == 0:
            theorem = "  \n✖ no robots: place at least one (a start needs robots to be solvable)"
        elif axis is not None:
            theorem = (
                f"  \n⚠ **unsolvable** (Theorem 1): mirror-symmetric about y = {axis:g}, a line through no "
                "robot (drawn) — no algorithm can form every pattern from it; move or add a robot"
            )
        else:
            theorem = "  \n✔ solvable: no horizontal mirror axis free of robots (Theorem 1)"
        return f"Robots: **{robot_count}** / targets: {draft_count}{theorem}"
    return f"Pattern: {draft_count} points for {robots} robots"


def next_phases(next_events: Sequence[str], click_advances: bool) -> str:
    """Manual: which robots are next for which phase."""
    by_phase: dict[str, list[int]] = {}
    for i, phase in enumerate(next_events):
        by_phase.setdefault(phase, []).append(i)
    parts = [
        f"{phase}: {', '.join(map(str, rs[:20]))}{'…' if len(rs) > 20 else ''}"
        for phase, rs in sorted(by_phase.items())
    ]
    head = (
        "Manual — click a robot to run its next phase."
        if click_advances
        else "Manual, Click: select — a click only selects; Step runs the selected robot's next phase."
    )
    return head + "  \n" + "  \n".join(parts)


def caption(e: Engine, sel: int | None, y_up: bool, seen: list[SeenRobot]) -> str:
    """The Selected robot panel: its light, phase, flip, and what its snapshot holds (stale or not)."""
    if sel is None:
        return "Click a robot to see what it sees and why it acts."
    st = e.state
    phase = ("idle", "looked", "computed")[st.phase[sel]]
    lines = [
        f"**Robot {sel}** — light `{st.lights[sel]}`, {phase}; next: {e.next_event(sel)}; "
        f"y-axis {'up' if y_up else 'flipped'}",
    ]
    if st.snapshot[sel] is None:
        lines.append(f"Idle: rays show the {len(e.visible(sel))} robots it would see if it looked now.")
        return "\n\n".join(lines)
    look = f"its snapshot from step {int(st.look_step[sel])} ({len(seen)} robots; rays go where it saw them)"
    changed = [s.describe() for s in seen if s.changed]
    if not changed:
        lines.append(f"It holds {look}. Nothing it saw has changed since: the snapshot is current.")
        return "\n\n".join(lines)
    shown = changed[:MAX_DIFFS]
    more = f"  \n… and {len(changed) - len(shown)} more" if len(changed) > len(shown) else ""
    lines.append(
        f"It holds {look}. **Stale**: {len(changed)} of them changed since (ghosts, in the light it "
        "saw, mark where):  \n" + "  \n".join(f"· {c}" for c in shown) + more
    )
    return "\n\n".join(lines)
