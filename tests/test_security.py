"""Nothing from a file or a browser chooses code (README, "Who can reach the server").

A trace names its algorithm; only built-in names, ``apf-opaque-grid@…`` resolution sets and the plug-ins
the command line loaded resolve. A name like ``os:abort`` is refused with one line, never imported."""

from __future__ import annotations

import builtins
import importlib
import json
import math
import subprocess
import sys

import pytest

from apf_viz.algorithms import algorithm_from_command_line, get_algorithm, load_plugin
from apf_viz.core.formats import InputError, trace_text
from apf_viz.core.run import advance, trace_header
from apf_viz.core.schedulers import make_scheduler
from apf_viz.ui.panels import Panels
from apf_viz.workbench.run_controller import MAX_SPEED
from apf_viz.workbench.session import Session

START = [(0, 0), (3, 0), (5, 0), (2, 2), (6, 2)]
PATTERN = [(0, 0), (1, 0), (2, 0), (0, 2), (1, 2)]
PLUGIN = "tests.plugin_algorithm:Hop"


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True)


def trace_naming(algorithm: str) -> str:
    header = {
        "format": "apf-viz-trace",
        "version": 1,
        "robots": [list(p) for p in START],
        "pattern": [list(p) for p in PATTERN],
        "scheduler": "async",
        "seed": 1,
        "algorithm": algorithm,
    }
    return json.dumps(header) + "\n"


def plugin_trace() -> str:
    """A real trace of a plug-in algorithm (its header names the algorithm by its own name)."""
    session = Session(START, PATTERN, algorithm=PLUGIN, plugins=load_plugin(PLUGIN), y_up=[True] * 5)
    advance(session.engine, make_scheduler("async"), 1)
    assert session.engine.outcome == "formed"
    return trace_text(trace_header(session.engine, "async", 1), session.engine.history.events())


@pytest.mark.parametrize("name", ["os:abort", "this:s", "subprocess:call", "builtins:breakpoint"])
def test_replay_refuses_a_trace_that_names_a_module(write_json, name):
    path = write_json("t.jsonl", trace_naming(name))
    proc = run_cli("replay", "--trace", str(path))
    assert proc.returncode == 2, (proc.returncode, proc.stderr)  # not killed by SIGABRT (-6)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and str(path) in lines[0] and "unknown algorithm" in lines[0], proc.stderr
    assert "--algorithm" in lines[0]  # says how to replay it with an algorithm of one's own
    assert "Beautiful is better than ugly" not in proc.stdout + proc.stderr  # `this` was never imported


def test_replay_with_an_algorithm_given_on_the_command_line(write_json):
    path = write_json("t.jsonl", plugin_trace())
    assert json.loads(path.read_text().splitlines()[0])["algorithm"] == "test-hop"
    unknown = run_cli("replay", "--trace", str(path))
    assert unknown.returncode == 2 and "unknown algorithm 'test-hop'" in unknown.stderr
    refused = run_cli("replay", "--trace", str(path), "--algorithm", "stay")
    assert refused.returncode == 2 and "differs on replay" in refused.stderr
    proc = run_cli("replay", "--trace", str(path), "--algorithm", PLUGIN, "--json")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["outcome"] == "formed"


def test_get_algorithm_never_imports():
    """Patched by hand, not with monkeypatch: pytest's own setattr may import while the patch is active
    (pytest 9.2 does), and the test must not depend on what a test tool does inside."""

    def forbidden(*args, **kwargs):
        raise AssertionError("get_algorithm imported a module")

    names = ("os:abort", "this:s", "apf_viz.algorithms.examples:Stay", "../../etc/passwd", "")
    outcomes: list[str] = []
    saved = (builtins.__import__, importlib.import_module)
    builtins.__import__, importlib.import_module = forbidden, forbidden
    try:
        for name in names:
            try:
                get_algorithm(name)
                outcomes.append("resolved")
            except ValueError as e:
                outcomes.append(str(e))
            except AssertionError as e:
                outcomes.append(f"imported: {e}")
        variant = get_algorithm("apf-opaque-grid@G1,G2").name
    finally:
        builtins.__import__, importlib.import_module = saved
    assert all(o.startswith("unknown algorithm") for o in outcomes), outcomes
    assert variant == "apf-opaque-grid@G1,G2"


def test_only_the_command_line_loads_a_plugin():
    algorithm, plugins = algorithm_from_command_line(PLUGIN)
    assert algorithm.name == "test-hop" and set(plugins) == {PLUGIN, "test-hop"}
    assert algorithm_from_command_line("stay")[1] == {}
    with pytest.raises(ValueError, match="cannot load algorithm"):
        algorithm_from_command_line("no_such_module_here:Thing")
    with pytest.raises(ValueError, match=r"cannot load algorithm .*TypeError"):
        load_plugin("apf_viz.core.grid:Direction")  # its constructor fails: one line, no traceback
    with pytest.raises(ValueError, match="has no attribute"):
        load_plugin("apf_viz.core.frames:random_y_up.__class__")  # no attribute paths
    with pytest.raises(ValueError, match="not an algorithm"):
        load_plugin("collections:OrderedDict")  # builds an object, but it has no decide()


def test_upload_trace_refuses_an_unknown_algorithm_and_keeps_the_run():
    session = Session(START, PATTERN, algorithm="apf-opaque-grid")
    session.step()
    before = (session.engine, session.engine.step_index, session.algorithm_name)
    for name in ("os:abort", "this:s", PLUGIN):
        with pytest.raises(InputError, match="unknown algorithm"):
            session.load_trace("t.jsonl", trace_naming(name).encode())
        assert (session.engine, session.engine.step_index, session.algorithm_name) == before


def test_upload_trace_of_a_plugin_the_command_line_loaded():
    text = plugin_trace().encode()
    with pytest.raises(InputError, match="unknown algorithm 'test-hop'"):
        Session(START, PATTERN, algorithm="stay").load_trace("t.jsonl", text)
    session = Session(START, PATTERN, algorithm=PLUGIN, plugins=load_plugin(PLUGIN))
    session.load_trace("t.jsonl", text)
    assert session.engine.algorithm.name == "test-hop"


def test_a_demo_is_chosen_by_name_from_the_list_never_by_path():
    loaded = []
    for name in ("../../pyproject", "/etc/passwd", "heart.json", "no-such-demo"):
        with pytest.raises(InputError, match="no demo called"):
            Panels._load_demo("", name, lambda filename, content: loaded.append(filename))
    Panels._load_demo("", "heart", lambda filename, content: loaded.append(filename))
    Panels._load_demo("starts", "demo-10", lambda filename, content: loaded.append(filename))
    assert loaded == ["heart.json", "demo-10.json"]


def test_values_a_browser_sends_are_checked():
    session = Session(START, PATTERN)
    for bad in (math.nan, math.inf, -1, 2**63, 1.5, "7"):
        with pytest.raises(InputError, match="seed"):
            session.set_seed(bad)  # type: ignore[arg-type]
    session.set_seed(7.0)
    assert session.seed == 7
    session.set_speed(math.inf)
    assert session.speed == MAX_SPEED
    session.set_speed(-3)
    assert session.speed == 1.0
    with pytest.raises(InputError):
        session.set_speed(math.nan)
    with pytest.raises(InputError):
        session.seek(math.nan)
    session.seek(10**30)  # clamped to the history
    assert session.engine.step_index == session.engine.history.length
    session.set_mode("edit-robots")
    with pytest.raises(InputError, match="outside the grid"):
        session.click((10**13, 0))
    assert (10**13, 0) not in session.editor.robots


def test_the_command_line_loads_only_classes_and_factory_functions(write_json):
    for spec in ("os:abort", "builtins:breakpoint", "os:getcwd"):
        with pytest.raises(ValueError, match="not an algorithm class or factory function"):
            load_plugin(spec)  # a builtin is never called
    with pytest.raises(ValueError, match="needs arguments"):
        load_plugin("apf_viz.core.frames:random_y_up")
    robots = write_json("r.json", {"robots": [list(p) for p in START]})
    pattern = write_json("p.json", {"points": [list(p) for p in PATTERN]})
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--algorithm", "os:abort")
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1, (proc.returncode, proc.stderr)
