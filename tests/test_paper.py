"""The paper on screen (issue #24): its three algorithms line by line, every rule id on a line, every line
reached by a rule, each resolution's line in place only where the variant has it."""

from __future__ import annotations

import re

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.rules import RULE_IDS
from apf_viz.core.portrayal import pseudocode_of
from apf_viz.ui.app import demo_session

FULL = get_algorithm("apf-opaque-grid").pseudocode()
LITERAL = get_algorithm("apf-opaque-grid-literal").pseudocode()


def test_every_rule_id_acts_on_a_line_or_says_why_none():
    for rule in RULE_IDS:
        keys = FULL.lines_of(rule)
        assert keys or rule in FULL.outside, f"{rule} has no line"
        assert all(FULL.line(k) is not None for k in keys), (rule, keys)
    assert all(reason for reason in FULL.outside.values())
    assert set(FULL.rules) - set(RULE_IDS) <= {r for r in FULL.rules if "/" in r}  # no stale rule ids


def test_every_numbered_line_is_reached_by_a_rule_or_listed_with_the_reason():
    reached = set()
    for keys in FULL.rules.values():
        for key in keys:
            reached |= {key, *FULL.enclosing(key)}
    numbered = {line.key for block in FULL.blocks for line in block.lines if line.number}
    assert numbered - reached == set(FULL.unreached), "a line no rule reaches, and no reason given"
    assert all(FULL.unreached.values())


def test_the_three_algorithms_are_numbered_as_the_paper_prints_them():
    titles = [b.title for b in FULL.blocks]
    assert titles[0].startswith("Algorithm 1") and titles[2].startswith("Algorithm 3")
    for block in LITERAL.blocks:
        numbers = [int(line.number) for line in block.lines if line.number]
        assert numbers == list(range(1, len(numbers) + 1))  # no gap, no repeat
    assert [b.lines[-1].number for b in LITERAL.blocks] == ["29", "47", "42"]


def test_a_resolutions_line_shows_only_in_a_variant_that_has_it():
    def lines(p):
        return {line.key: line for block in p.blocks for line in block.lines}

    full, literal = lines(FULL), lines(LITERAL)
    added = {k: line for k, line in full.items() if line.resolution}
    assert {line.resolution for line in added.values()} == {
        "G1", "G2", "G3", "E2", "KD", "NV", "LW", "SD", "L2", "P3", "LA", "N2", "G4", "G5",
    }  # fmt: skip
    assert all(line.why for line in added.values())  # its name and a one-sentence reason
    assert {line.resolution for line in literal.values() if line.resolution} == {"LA"}  # the paper + LA
    assert full["A2.33"].replaced and not literal["A2.33"].replaced  # NV rewrites the leader1 test
    g1 = get_algorithm("apf-opaque-grid@G1").pseudocode()
    assert "G1@A1.2" in lines(g1) and "G2@A1.8" not in lines(g1)


def test_lines_of_a_composite_rule_take_its_context():
    assert FULL.lines_of("A3.off.grow-line/LineMove.along") == ("A3.14", "A3.33")
    assert FULL.lines_of("A3.off.next-target/TargetMove.done") == ("A3.17",)  # not 8 or 26
    assert FULL.enclosing("A1.15") == ("A1.14", "A1.13", "A1.10", "A1.9", "A1.8")


@pytest.mark.parametrize("algorithm", ["apf-opaque-grid", "apf-opaque-grid-literal"])
def test_every_rule_the_demo_fires_has_its_line_in_that_variants_paper(algorithm):
    s = demo_session()
    s.set_algorithm(algorithm)
    paper = pseudocode_of(s.engine.algorithm)
    fired = set()
    while s.step():
        pass
    for step in s.engine.history.steps[: s.engine.history.length]:
        fired |= {ev.rule_id for ev in step.events if ev.phase == "compute" and ev.rule_id}
    assert len(fired) >= 10
    for rule in fired:
        keys = paper.lines_of(rule)
        assert keys or rule in paper.outside, rule
        assert all(paper.line(k) is not None for k in keys), (rule, keys)  # shown in this variant


def test_each_rule_text_cites_the_lines_the_panel_highlights():
    from apf_viz.algorithms.apf_opaque_grid.paper import citation

    cited = 0
    for rule, text in RULE_IDS.items():
        said = re.search(r"\((lines? [0-9–]+)", text)
        if said:
            cited += 1
            assert said.group(1) == citation(FULL, rule), rule
    assert cited >= 25


def test_the_paper_panel_marks_the_decisions_line_and_its_conditions():
    from apf_viz.workbench.view_model.paper import paper_html

    text = paper_html(FULL, (4, "A1.terminal1.dominant"), "apf-opaque-grid")
    assert "Algorithm 1" in text and "Robot 4" in text
    hit = text.split("data-hit", 1)[1].split("</div></div>", 1)[0]
    assert "r.light ← leader1" in hit  # line 15, the decision's action
    assert text.count("#fff6cc") == len(FULL.enclosing("A1.15"))  # its five enclosing conditions
    assert "[G2]" in text and "[G1]" in text  # this variant's resolution lines, named
    literal = paper_html(LITERAL, (4, "A1.terminal1.dominant"), "apf-opaque-grid-literal")
    assert "[G2]" not in literal and "[G1]" not in literal  # gone with the literal paper
    none = paper_html(FULL, (2, "done"), "apf-opaque-grid")
    assert "has no line in the paper" in none and "never acts again" in none
    assert "gives no pseudocode" in paper_html(None, None, "compact-left")


def test_the_view_shows_the_selected_robots_decision_else_the_runs_last():
    s = demo_session()
    for _ in range(30):
        s.step()
    run_last = s.view().paper_decision
    assert run_last is not None and run_last[1] in s.view().paper_text
    s.selected = next(
        r for r in range(s.engine.k) if s.engine.state.decided[r] is not None and r != run_last[0]
    )
    v = s.view()
    assert v.paper_decision[0] == s.selected and f"Robot {s.selected}:" in v.paper_text
