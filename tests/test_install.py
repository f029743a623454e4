"""Installable anywhere: a wheel carries the demo patterns, and an installed apf-viz serves the demo from
any folder (the top-level demo_patterns/ is the source; pyproject.toml ships it inside the package)."""

from __future__ import annotations

import json
import os
import shutil
import site
import subprocess
import sys
import time
import urllib.request
import venv
from pathlib import Path

import pytest

from apf_viz.demos import NOT_PATTERNS
from apf_viz.ui.app import free_port

ROOT = Path(__file__).resolve().parent.parent
IGNORED = (".git", ".venv", "build", "*.egg-info", "__pycache__", "test-output", ".hypothesis", ".*_cache")


def _see_the_running_environment(python: Path) -> None:
    """Let a fresh venv import the dependencies installed for this test run (numpy, viser, ...), so that
    only the wheel is installed into it, with no download.

    ``system_site_packages`` would give the *base* interpreter's packages, not those of the venv the
    tests run in (where the README's commands installed them): name this interpreter's site-packages
    in a .pth file instead. Lines of a .pth file only extend ``sys.path``; the .pth files inside those
    folders are not processed, so the editable install of this checkout stays invisible, and the venv's
    own site-packages (the wheel) comes first."""
    own = subprocess.run(
        [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    outer = [p for p in (*site.getsitepackages(), site.getusersitepackages()) if Path(p).is_dir()]
    (Path(own) / "_apf_viz_test_outer.pth").write_text("\n".join(outer) + "\n")


@pytest.mark.slow
def test_a_wheel_installed_in_a_fresh_venv_finds_its_demos_and_serves(tmp_path):
    source = tmp_path / "source"  # a copy: a build leaves build/ and egg-info behind, and may reuse them
    shutil.copytree(ROOT, source, ignore=shutil.ignore_patterns(*IGNORED))
    wheels = tmp_path / "wheels"
    built = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(wheels), str(source)],
        capture_output=True,
        text=True,
    )
    assert built.returncode == 0, built.stderr[-2000:]
    (wheel,) = wheels.glob("apf_viz-*.whl")
    env_dir = tmp_path / "venv"
    venv.EnvBuilder(system_site_packages=False, with_pip=True).create(env_dir)
    python = env_dir / "bin" / "python"
    _see_the_running_environment(python)
    installed = subprocess.run(
        [str(python), "-m", "pip", "install", "-q", "--no-deps", str(wheel)], capture_output=True, text=True
    )
    assert installed.returncode == 0, installed.stderr[-2000:]
    elsewhere = tmp_path / "elsewhere"  # not the repository: nothing found by the working directory
    elsewhere.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    probe = subprocess.run(
        [
            str(python),
            "-c",
            "import json, apf_viz, apf_viz.demos as d, apf_viz.lecture as l; "
            "from apf_viz.algorithms.apf_opaque_grid import paper; "
            "print(json.dumps([apf_viz.__file__, str(d.DEMO_START), sorted(d.demo_files()), "
            "sorted(d.demo_files('starts')), [{r: p.is_file() for r, p in s.files().items()} "
            "for s in d.scenarios().values()], sorted(l.lectures()), len(l.figures()), "
            "paper.SOURCE.is_file()]))",
        ],
        cwd=elsewhere,
        env=env,
        capture_output=True,
        text=True,
    )
    assert probe.returncode == 0, probe.stderr
    module, start, patterns, starts, scenario_files, shipped_lectures, figures, paper = json.loads(
        probe.stdout
    )
    assert Path(module).is_relative_to(env_dir)  # the installed copy, not this checkout
    assert Path(start).is_relative_to(env_dir) and Path(start).is_file()
    assert patterns == sorted(
        p.stem for p in (ROOT / "demo_patterns").glob("*.json") if p.name not in NOT_PATTERNS
    )
    # The paper on screen and its lectures ship too: the pseudocode, the figures, the lectures.
    assert (
        paper
        and figures >= 20
        and len(shipped_lectures) == len(list((ROOT / "demo_patterns" / "lectures").glob("*.json")))
    )
    assert scenario_files and all(all(found.values()) for found in scenario_files)  # traces shipped too
    # What ships, by name, from anywhere: a lecture checked, a run of a shipped start and pattern, the
    # manual's pages (the help texts name them).
    cli = str(env_dir / "bin" / "apf-viz")
    for argv, said in (
        (["lecture", "check", "what-a-robot-cannot-see"], "stops reached, their claims true"),
        (["run", "--robots", "sym-call-7", "--pattern", "cup-7"], "formed:"),
        (["docs", "guide"], "# The visualiser: a guide"),
        (["demos"], "Heart from 10 robots"),
    ):
        done = subprocess.run([cli, *argv], cwd=elsewhere, env=env, capture_output=True, text=True)
        assert done.returncode == 0 and said in done.stdout, (argv, done.stdout[-500:], done.stderr[-500:])
    assert starts == sorted(p.stem for p in (ROOT / "demo_patterns" / "starts").glob("*.json"))
    port = free_port()
    server = subprocess.Popen(
        [str(env_dir / "bin" / "apf-viz"), "--port", str(port)],
        cwd=elsewhere,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.time() + 90
        while True:
            assert server.poll() is None, server.stderr.read()
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=2) as page:
                    assert page.status == 200
                    break
            except OSError:
                assert time.time() < deadline, "the installed apf-viz did not serve the demo"
                time.sleep(0.3)
    finally:
        server.terminate()
        server.communicate(timeout=60)
