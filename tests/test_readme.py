"""The manual's command-line examples (docs/CLI.md) run as written (a snippet that is executed cannot
drift); the README stays a front page."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


CLI = ROOT / "docs" / "CLI.md"


def readme_commands() -> list[str]:
    text = CLI.read_text()
    block = re.search(r"## Examples\n\n.*?```bash\n(.*?)```", text, re.S).group(1)
    joined = block.replace("\\\n", " ")
    return [line.split("#")[0].strip() for line in joined.splitlines() if line.startswith("apf-viz ")]


def test_readme_examples_run(tmp_path):
    commands = readme_commands()
    assert len(commands) >= 5
    for cmd in commands:
        if "..." in cmd:
            continue  # an elided variation of the line above it
        args = shlex.split(cmd.split(">")[0])[1:]
        proc = subprocess.run(
            [sys.executable, "-m", "apf_viz.cli", *args],
            cwd=tmp_path,
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert proc.returncode in (0, 1), (cmd, proc.stderr)
        assert "Traceback" not in proc.stderr


def test_the_playing_the_adversary_commands_run_as_written(tmp_path):
    """The block is run by bash as it stands, with ``apf-viz`` this checkout's CLI; exit 1 (ran, not
    formed) is a result, anything else stops the block."""
    text = CLI.read_text()
    section = text[text.index("## Playing the adversary") :]
    block = re.search(r"```bash\n(.*?)```", section, re.S).group(1)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    shim = bin_dir / "apf-viz"
    shim.write_text(f'#!/bin/sh\n"{sys.executable}" -m apf_viz.cli "$@"\nc=$?\n[ $c -le 1 ] || exit $c\n')
    shim.chmod(0o755)
    (tmp_path / "demo_patterns").symlink_to(ROOT / "demo_patterns")
    (tmp_path / "tests").symlink_to(ROOT / "tests")
    env = {"PATH": f"{bin_dir}:/usr/bin:/bin", "PYTHONPATH": str(ROOT), "HOME": str(tmp_path)}
    proc = subprocess.run(
        ["bash", "-euo", "pipefail", "-c", block], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr and "error" not in proc.stderr, proc.stderr
    assert (tmp_path / "l2.robots.json").is_file() and (tmp_path / "start-of-s.jsonl").is_file()


def test_the_project_dates_its_figures_by_date_and_commit_never_by_work_session():
    """A figure is dated by its date and its commit; the text never counts working sessions ("session 18's
    code", "this session"). ``Session`` the class (one server's shared state) is a name, not a date."""
    dating = re.compile(r"\b(session \d+|sessions? \d+|this session|previous session|last session)\b", re.I)
    files = [ROOT / "README.md", *(ROOT / "docs").glob("*.md"), *(ROOT / "apf_viz").rglob("*.py")]
    files += [
        *(ROOT / "tests").glob("*.py"),
        *(ROOT / "benchmarks").glob("*.py"),
        *(ROOT / "scripts").glob("*"),
    ]
    found = [
        f"{path.relative_to(ROOT)}:{n}"
        for path in files
        if path.is_file() and path.name != "test_readme.py"
        for n, line in enumerate(path.read_text(errors="replace").splitlines(), 1)
        if dating.search(line)
    ]
    assert not found, found


def _slug(heading: str) -> str:
    """A heading's anchor as GitHub makes it: lower case, punctuation dropped, spaces as hyphens."""
    kept = "".join(c for c in heading.strip().lower() if c.isalnum() or c in " -_")
    return kept.replace(" ", "-")


def test_the_readme_is_a_front_page_and_every_link_of_the_manual_resolves():
    """README.md at most 150 lines; every relative link of it and of docs/ names a file that exists,
    and an anchor a heading of that file."""
    readme = ROOT / "README.md"
    assert len(readme.read_text().splitlines()) <= 150
    broken = []
    for page in [readme, ROOT / "CHANGELOG.md", *(ROOT / "docs").glob("*.md")]:
        text = page.read_text()
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if target.startswith(("http://", "https://", "mailto:")):
                continue
            path, _, anchor = target.partition("#")
            file = (page.parent / path).resolve() if path else page
            if not file.exists():
                broken.append(f"{page.name}: {target}")
            elif anchor and file.suffix == ".md":
                headings = re.findall(r"^#+ (.+)$", file.read_text(), re.M)
                if anchor not in {_slug(h) for h in headings}:
                    broken.append(f"{page.name}: {target} (no such heading)")
    assert broken == []


def test_every_command_line_of_the_front_page_and_the_manual_parses():
    """Each ``apf-viz …`` line of a shell block (README, docs/; ARCHITECTURE's Extending adds commands of
    its own) is accepted by the real parser: no option the parser does not know, no choice it refuses."""
    from apf_viz.cli import build_parser

    pages = [ROOT / "README.md", *(p for p in (ROOT / "docs").glob("*.md") if p.name != "ARCHITECTURE.md")]
    refused, seen = [], 0
    for page in pages:
        for block in re.findall(r"```(?:bash|console|sh)\n(.*?)```", page.read_text(), re.S):
            for line in block.replace("\\\n", " ").splitlines():
                line = line.removeprefix("$ ").split(" #")[0].split(" > ")[0].split(" | ")[0].strip()
                if not line.startswith("apf-viz ") or "..." in line or "…" in line:
                    continue
                if "[" in line or re.search(r"(?<![\w.-])[A-Z][A-Z_|]+(?![\w.-])", line):
                    continue  # a synopsis ([--option]) or a placeholder (SEED, NAME|FILE), not a command
                line = re.sub(r"\$\w+", "1", line)  # a shell loop's variable: a number in its place
                seen += 1
                try:
                    build_parser().parse_args(shlex.split(line)[1:])
                except SystemExit as stop:
                    if stop.code:
                        refused.append(f"{page.name}: {line}")
    assert seen >= 20 and refused == []
