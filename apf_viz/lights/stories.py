"""A counterexample's story in words: where the hidden light first shows, and how the run ends."""

from __future__ import annotations

from pathlib import Path

from apf_viz.algorithms.merged_lights import MergedLights, split_name
from apf_viz.core.budget import EVENTS_PER_MOVE, MOVES_PER_KD


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
    verdict = header.options.get("verdict", engine.outcome or "limit")  # a trace that stops running: its cap
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
        return (
            f"then it runs on without forming until its budget, {MOVES_PER_KD}·k·D moves or "
            f"{EVENTS_PER_MOVE} events a move "
            f"({engine.state.moves:,} moves, {len(events):,} events)"
        )
    return f"then {header.options.get('detail', verdict)}"


def _robots(rs: list[int]) -> str:
    return f"robot {rs[0]}" if len(rs) == 1 else "robots " + ", ".join(map(str, rs))
