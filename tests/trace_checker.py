"""An independent trace checker: it shares no code with the engine (only json and the lattice walk of
tests/oracle.py).

It replays a trace file and checks: each robot's events run Look → Compute → Move in order; every Look's
``sees`` is exactly the set of robots visible at that moment; no two robots ever share a point; every
Move goes where the preceding Compute said (one edge, or nowhere for a stay).
"""

from __future__ import annotations

import json
from pathlib import Path

from tests.oracle import visible_by_lattice_walk as _visible

_NEXT = {"look": "compute", "compute": "move", "move": "look"}
_DELTA = {"left": (-1, 0), "right": (1, 0), "up": (0, 1), "down": (0, -1), None: (0, 0)}


def check_trace(path: Path) -> dict:
    lines = [json.loads(line) for line in Path(path).read_text().splitlines() if line.strip()]
    header, events = lines[0], lines[1:]
    assert header["format"] == "apf-viz-trace" and header["version"] == 1
    pos = [tuple(p) for p in header["robots"]]
    expected = ["look"] * len(pos)
    pending: dict[int, tuple[int, int]] = {}
    stale_moves = 0
    look_at: dict[int, int] = {}
    last_change = -1
    pending_round_moves: list[tuple[int, tuple[int, int]]] = []
    for n, e in enumerate(events):
        r, phase = e["robot"], e["phase"]
        assert phase == expected[r], f"event {n}: robot {r} did {phase}, expected {expected[r]}"
        expected[r] = _NEXT[phase]
        if phase == "look":
            assert sorted(e["sees"]) == _visible(pos, r), f"event {n}: robot {r} sees {e['sees']}"
            look_at[r] = n
        elif phase == "compute":
            pending[r] = _DELTA[e["move"]]
        else:
            dx, dy = pending.pop(r)
            assert tuple(e["to"]) == (pos[r][0] + dx, pos[r][1] + dy), f"event {n}: move of {r} off its plan"
            if last_change > look_at[r]:
                stale_moves += 1
            if e.get("round") is not None:
                pending_round_moves.append((r, tuple(e["to"])))
                nxt = events[n + 1] if n + 1 < len(events) else None
                if nxt is not None and nxt["phase"] == "move" and nxt.get("round") == e["round"]:
                    continue  # simultaneous: apply the whole round's moves together
                moves, pending_round_moves = pending_round_moves, []
            else:
                moves = [(r, tuple(e["to"]))]
            for rr, to in moves:
                if to != pos[rr]:
                    last_change = n
                pos[rr] = to
            assert len(set(pos)) == len(pos), f"event {n}: collision"
    return {"final": pos, "stale_moves": stale_moves, "events": len(events)}
