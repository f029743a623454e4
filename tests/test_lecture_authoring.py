"""A lecture written without serving it: ``apf-viz lecture rules`` lists every rule id a stop may run to,
and ``apf-viz lecture show`` prints a start with the robot numbers, lights and mirror axis a stop's
``select``, ``expect`` and words refer to, the same as the page numbers them."""

from __future__ import annotations

import pytest

from apf_viz.algorithms.apf_opaque_grid.rules import RULE_IDS
from apf_viz.cli import main
from apf_viz.lecture import find_lecture
from apf_viz.workbench.session import Session


def test_rules_lists_every_rule_id_of_the_algorithm_with_its_words(capsys):
    assert main(["lecture", "rules"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"apf-opaque-grid: {len(RULE_IDS)} rule ids")
    for rule, words in RULE_IDS.items():
        assert f"  {rule} " in out and words in out
    every_rule_a_shipped_lecture_names = {
        stop.until.rule
        for name in ("algorithm-in-12-stops", "what-a-robot-cannot-see", "where-the-paper-breaks")
        for stop in find_lecture(name).stops
        if stop.until is not None and stop.until.rule is not None
    }
    assert all(rule.split("/")[0] in out for rule in every_rule_a_shipped_lecture_names)


def test_show_numbers_the_robots_as_the_page_does_and_names_the_mirror_axis(capsys):
    assert main(["lecture", "show", "Symmetric start that needs call"]) == 0
    out = capsys.readouterr().out
    s = Session([(0, 0)], [(0, 0)])
    s.load_scenario("Symmetric start that needs call")
    for i, robot in enumerate(s.view().robots):  # the numbers the page draws beside the robots
        axis = "up  " if s.engine.y_up[i] else "down"
        assert f"robot {i:>3} at {robot.position}, +y {axis}, light {robot.light}" in out
    assert "mirror axis: y = 1, through robot 5 (the paper's K)" in out
    assert main(["lecture", "show", "Unsolvable box"]) == 0
    assert "through no robot: unsolvable (Theorem 1)" in capsys.readouterr().out
    assert main(["lecture", "show", "sym-call-7", "--pattern", "cup-7"]) == 0
    assert "sym-call-7.json: 7 robots" in capsys.readouterr().out


def test_show_without_a_known_start_is_one_line(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["lecture", "show", "no such start"])
    assert exit_.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "not a Demo scenario" in err
