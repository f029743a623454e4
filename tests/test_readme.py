"""The README's command-line examples run as written (a snippet that is executed cannot drift)."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def readme_commands() -> list[str]:
    text = (ROOT / "README.md").read_text()
    block = re.search(r"## Command line\n\n```bash\n(.*?)```", text, re.S).group(1)
    joined = block.replace("\\\n", " ")
    return [line.split("#")[0].strip() for line in joined.splitlines() if line.startswith("apf-viz ")]


def test_readme_examples_run(tmp_path):
    commands = readme_commands()
    assert len(commands) >= 5
    for cmd in commands:
        if "..." in cmd:
            continue  # an elided variation of the line above it
        args = shlex.split(cmd.split(">")[0])[1:]
        args = [str(ROOT / a) if (ROOT / a).exists() else a for a in args]
        proc = subprocess.run(
            [sys.executable, "-m", "apf_viz.cli", *args],
            cwd=tmp_path,
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert proc.returncode in (0, 1), (cmd, proc.stderr)
        assert "Traceback" not in proc.stderr
