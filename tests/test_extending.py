"""docs/ARCHITECTURE.md's "Extending", followed step by step in a copy of the package: each file written
as shown, each list edited as shown, each command run and its output compared with what the page says."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "ARCHITECTURE.md"
BLOCK = re.compile(r"^```(\w+)(?: (new|)\s*([^\n]*))?\n(.*?)^```\n", re.M | re.S)


def _section(name: str) -> str:
    text = DOC.read_text()
    start = text.index(f"## {name}\n")
    end = text.find("\n## ", start + 1)
    return text[start : end if end != -1 else len(text)]


def _apply_diff(path: Path, body: str) -> None:
    """A diff block of the page: context lines (one space) and added lines (+), found once in the file."""
    lines = body.splitlines()
    assert all(line[:1] in (" ", "+") for line in lines), body
    before = "".join(line[1:] + "\n" for line in lines if line.startswith(" "))
    after = "".join(line[1:] + "\n" for line in lines)
    text = path.read_text()
    assert text.count(before) == 1, f"{path}: the page's context is not found once:\n{before}"
    path.write_text(text.replace(before, after))


def _run_console(where: Path, body: str) -> None:
    """Each ``$`` line run (``apf-viz`` as ``python -m apf_viz.cli`` of the copy); the lines after it are
    its output: all of it for apf-viz, one run of lines of it for a script (a library may print its own
    banner around them)."""
    commands: list[tuple[str, list[str]]] = []
    for line in body.splitlines():
        if line.startswith("$ "):
            commands.append((line[2:], []))
        else:
            commands[-1][1].append(line)
    for command, expected in commands:
        argv = command.split()
        argv = (
            [sys.executable, "-m", "apf_viz.cli", *argv[1:]]
            if argv[0] == "apf-viz"
            else [sys.executable, *argv[1:]]
        )
        done = subprocess.run(argv, cwd=where, capture_output=True, text=True, timeout=600)
        assert done.returncode in (0, 1), (command, done.stderr)
        shown = [line for line in done.stdout.splitlines() if line.strip()]
        if argv[1:3] == ["-m", "apf_viz.cli"]:
            assert shown == expected, (command, done.stdout, done.stderr)
        else:
            n = len(expected)
            assert any(shown[i : i + n] == expected for i in range(len(shown))), (command, done.stdout)


def test_every_extending_example_works_as_the_page_shows(tmp_path):
    """Schedulers, a command, an algorithm, a panel and a lecture, in the order of the page (the later
    examples use the robots file the first one writes)."""
    copy = tmp_path / "house"
    copy.mkdir()
    ignore = shutil.ignore_patterns("__pycache__")
    shutil.copytree(ROOT / "apf_viz", copy / "apf_viz", ignore=ignore)
    shutil.copytree(ROOT / "demo_patterns", copy / "demo_patterns", ignore=ignore)
    section = _section("Extending")
    kinds = []
    for lang, new, target, body in BLOCK.findall(section):
        if new == "new":
            assert not (copy / target).exists(), target
            (copy / target).write_text(body)
        elif lang == "diff":
            _apply_diff(copy / target, body)
        elif lang == "console":
            _run_console(copy, body)
        kinds.append(lang)
    assert kinds.count("console") == 5 and kinds.count("diff") == 8  # every example was followed
    # What the page claims beyond its outputs: the new scheduler reaches the visualiser's dropdown and
    # the light lab, the new command the help, the new algorithm the registry.
    probe = (
        "from apf_viz.workbench.session import SCHEDULER_LABELS; "
        "from apf_viz.lights import RANDOM_SCHEDULERS; "
        "from apf_viz.algorithms import ALGORITHMS; "
        "print(SCHEDULER_LABELS['lowest-first'], 'lowest-first' in RANDOM_SCHEDULERS, 'lamp' in ALGORITHMS)"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe], cwd=copy, capture_output=True, text=True, timeout=120
    )
    assert done.stdout.split() == ["lowest-first", "True", "True"], done.stderr
    help_text = subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", "--help"], cwd=copy, capture_output=True, text=True, timeout=120
    ).stdout
    assert "count" in help_text
