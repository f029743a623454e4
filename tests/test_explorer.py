"""The exhaustive explorer: broken toys are caught with minimal, replayable counterexamples; the state
count matches a brute-force enumeration with the real engine; a budget never says verified."""

from __future__ import annotations

import json
import subprocess
import sys
from collections import deque

from apf_viz.algorithms import get_algorithm
from apf_viz.core.algorithm import Decision
from apf_viz.core.engine import Engine
from apf_viz.core.engine_state import Phase
from apf_viz.core.formats import load_trace
from apf_viz.core.grid import Direction
from apf_viz.core.run import engine_for_trace, replay
from apf_viz.explore.check import counterexample_engine
from apf_viz.explore.explorer import Explorer


class StepUpIfFree:
    """Moves up (local) once if the point above looks free: on stale views two robots can meet."""

    name = "step-up"
    lights = ("off", "done")

    def decide(self, view, pattern):
        if view.light == "off" and view.at(0, 1) is None:
            return Decision("done", Direction.UP, "point above free: move up")
        return Decision("done", None, "done")


class Stay:
    name = "stay-toy"
    lights = ("off",)

    def decide(self, view, pattern):
        return Decision("off", None, "stay")


class Toggle:
    """Never settles: every Compute flips the light."""

    name = "toggle"
    lights = ("off", "done")

    def decide(self, view, pattern):
        return Decision("done" if view.light == "off" else "off", None, "toggle")


def test_a_collision_is_found_with_the_shortest_schedule_and_replays():
    start, pattern, y_up = [(0, 0), (0, 2)], [(0, 0), (0, 1)], [True, False]  # both aim at (0, 1)
    result = Explorer(StepUpIfFree(), start, pattern, y_up).run()
    assert result.verdict == "collision"
    assert len(result.schedule) == 6  # both Look and Compute before either moves: nothing shorter exists
    e = counterexample_engine(StepUpIfFree(), start, pattern, y_up, "async", result)
    assert e.outcome == "collision"


def test_a_deadlock_is_found():
    result = Explorer(Stay(), [(0, 0), (2, 0)], [(0, 0), (1, 0)], [True, True]).run()
    assert result.verdict == "deadlock" and result.schedule == []


def test_a_livelock_is_found_as_a_fair_lasso():
    result = Explorer(Toggle(), [(0, 0), (2, 0)], [(0, 0), (0, 2)], [True, True]).run()
    assert result.verdict == "livelock" and result.loop_start is not None
    loop = result.schedule[result.loop_start :]
    assert {r for step in loop for r in step} == {0, 1}  # every robot acts in the loop


def test_the_papers_literal_n2_livelock_is_found():
    result = Explorer(
        get_algorithm("apf-opaque-grid-literal"), [(0, 0), (1, 0)], [(0, 0), (0, 1)], [True, True]
    ).run()
    assert result.verdict == "livelock"


def test_verified_small_start_and_budget_never_says_verified():
    algorithm = get_algorithm("apf-opaque-grid")
    full = Explorer(algorithm, [(0, 0), (2, 1), (3, -1)], [(0, 0), (1, 0), (2, 0)], [True] * 3).run()
    assert full.verdict == "verified"
    for budget in (1, 10, full.states - 1):
        r = Explorer(
            algorithm, [(0, 0), (2, 1), (3, -1)], [(0, 0), (1, 0), (2, 0)], [True] * 3, max_states=budget
        ).run()
        assert r.verdict == "budget"


def _engine_key(e: Engine) -> tuple:
    st = e.state
    pts = e.current_points()
    mx, my = min(p[0] for p in pts), min(p[1] for p in pts)
    held = []
    for r in range(e.k):
        if st.phase[r] == Phase.LOOKED:
            held.append(e.decide(st.snapshot[r]))
        elif st.phase[r] == Phase.COMPUTED:
            held.append(st.pending[r])
        else:
            held.append(None)
    return (
        tuple((x - mx, y - my) for x, y in pts),
        tuple(st.lights),
        tuple(int(p) for p in st.phase),
        tuple(held),
    )


def test_reachable_state_count_matches_brute_force_with_the_engine():
    start, pattern, y_up = [(0, 0), (1, 0)], [(0, 0), (0, 1)], [True, False]
    algorithm = get_algorithm("apf-opaque-grid")
    explored = Explorer(algorithm, start, pattern, y_up).run()
    assert explored.verdict == "verified"
    seen = set()
    queue = deque([()])
    while queue:
        schedule = queue.popleft()
        e = Engine(start, pattern, algorithm, y_up=y_up)
        for r in schedule:
            e.state.outcome = None  # keep stepping past a quiescent state, as the explorer does
            e.step([r])
        key = _engine_key(e)
        if key in seen:
            continue
        seen.add(key)
        queue.extend((*schedule, r) for r in range(e.k))
    assert len(seen) == explored.states


def test_cli_check_exit_codes_and_counterexample(tmp_path, write_json):
    robots = write_json("r.json", {"robots": [[0, 0], [1, 0]]})
    pattern = write_json("p.json", {"points": [[0, 0], [0, 1]]})
    out = tmp_path / "cex.jsonl"

    def cli(*args):
        return subprocess.run(
            [
                sys.executable,
                "-m",
                "apf_viz.cli",
                "check",
                "--robots",
                str(robots),
                "--pattern",
                str(pattern),
                "--json",
                *args,
            ],
            capture_output=True,
            text=True,
        )

    ok = cli()
    assert ok.returncode == 0 and json.loads(ok.stdout)["verdict"] == "verified"
    every = cli("--no-reduction")  # every interleaving: the same verdict, more states
    assert every.returncode == 0 and json.loads(every.stdout)["verdict"] == "verified"
    assert json.loads(every.stdout)["states"] > json.loads(ok.stdout)["states"]
    bad = cli("--algorithm", "apf-opaque-grid-literal", "--counterexample", str(out))
    assert bad.returncode == 1 and json.loads(bad.stdout)["verdict"] == "livelock"
    header, events = load_trace(out)
    assert header.options["verdict"] == "livelock"
    e = engine_for_trace(header, get_algorithm(header.algorithm))
    replay(e, events, str(out))
    budget = cli("--max-states", "5")
    assert budget.returncode == 4 and json.loads(budget.stdout)["verdict"] == "budget"
    flips = cli("--flips", "all")
    assert flips.returncode == 0


def test_the_lockstep_finding_and_its_fix():
    """Without L2, two leader1 robots walk left in lockstep forever on C2 under the default light
    semantics; with lc-atomic the race that makes the second leader1 cannot happen; with L2 it is
    verified (docs/VERIFICATION.md)."""
    from apf_viz.algorithms.apf_opaque_grid.resolutions import RESOLUTIONS

    without_l2 = get_algorithm("apf-opaque-grid@" + ",".join(r for r in RESOLUTIONS if r != "L2"))
    start, pattern = [(0, 0), (0, 2), (1, 0), (1, 3)], [(0, 0), (1, 0), (2, 0), (3, 0)]
    # With the partial-order reduction (the same verdicts: test_partial_order.py): 20 s → 1 s.
    assert Explorer(without_l2, start, pattern, [True] * 4, reduction=True).run().verdict == "escape"
    lca = Explorer(without_l2, start, pattern, [True] * 4, light_semantics="lc-atomic", reduction=True).run()
    assert lca.verdict == "verified"
    default = Explorer(get_algorithm("apf-opaque-grid"), start, pattern, [True] * 4, reduction=True).run()
    assert default.verdict == "verified"
