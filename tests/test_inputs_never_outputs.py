"""An input is never an output, and an input is only ever a regular file: every command refuses, in one
line with exit 2, an output that names one of its inputs (by the same path, a symbolic link or a hard
link) and an input that is a FIFO, and leaves the input as it was."""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz.core.files import InputError, inputs_guarded, read_text, write_atomic

ROOT = Path(__file__).resolve().parent.parent
DEMOS = ROOT / "demo_patterns"
TRACE = DEMOS / "traces" / "literal-collision-4.jsonl"
ROBOTS, PATTERN = DEMOS / "starts" / "sym-call-7.json", DEMOS / "cup-7.json"
LECTURE = DEMOS / "lectures" / "algorithm-in-12-stops.json"


def run_cli(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True, cwd=cwd, timeout=120
    )


def one_line_exit_2(out: subprocess.CompletedProcess, *needles: str) -> None:
    assert out.returncode == 2, (out.returncode, out.stdout, out.stderr)
    errors = [line for line in out.stderr.splitlines() if "error" in line]
    assert len(errors) == 1 and "Traceback" not in out.stderr, out.stderr
    for needle in needles:
        assert needle in errors[0], out.stderr


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def own_input_commands(t: Path, r: Path) -> list[tuple[list[str], str]]:
    """Each command given one of its inputs (``t`` a trace, ``r`` a robots file) as the value of its
    output option, with that option."""
    run = ["run", "--robots", str(r), "--pattern", str(PATTERN), "--max-events", "20"]
    return [
        (["export", "--trace", str(t)], "--out"),
        (["figure", "--trace", str(t)], "--out"),
        (["schedule", "--from-trace", str(t)], "--out"),
        (["schedule", "--from-trace", str(t)], "--robots-out"),
        (run, "--trace"),
        (run, "--schedule-out"),
        (["check", "--robots", str(r), "--pattern", str(PATTERN)], "--counterexample"),
    ]


@pytest.mark.parametrize("how", ["same path", "symbolic link", "hard link"])
def test_no_command_writes_over_its_own_input(tmp_path, how):
    t, r = tmp_path / "t.jsonl", tmp_path / "r.json"
    shutil.copy(TRACE, t)
    shutil.copy(ROBOTS, r)
    before = {t: digest(t), r: digest(r)}
    for command, option in own_input_commands(t, r):
        target = t if command[0] in ("export", "figure", "schedule") else r
        if how != "same path":
            alias = tmp_path / f"alias-{target.name}"
            alias.unlink(missing_ok=True)
            (alias.symlink_to if how == "symbolic link" else alias.hardlink_to)(target)
            target = alias
        out = run_cli(*command, option, str(target), cwd=tmp_path)
        one_line_exit_2(out, "is the same file as", "an output never replaces an input")
        assert {p: digest(p) for p in before} == before, command
        assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary file left


def test_two_outputs_of_one_command_may_not_name_one_file(tmp_path):
    out = run_cli("schedule", "--from-trace", str(TRACE), "--out", "s", "--pattern-out", "s", cwd=tmp_path)
    one_line_exit_2(out, "s: is the same file as --out s")
    assert not (tmp_path / "s").exists()


def test_an_input_named_by_a_word_not_a_path_is_kept_too(tmp_path):
    """``--lecture`` takes a name or a file: the guard is on what was read, not on the options' types."""
    lecture = tmp_path / "lecture.json"
    shutil.copy(LECTURE, lecture)
    before = digest(lecture)
    out = run_cli("export", "--lecture", str(lecture), "--out", str(lecture), cwd=tmp_path)
    one_line_exit_2(out, "is this command's input", "refusing to write over an input")
    assert digest(lecture) == before


def test_a_file_read_while_guarded_is_never_replaced(tmp_path):
    """The guard behind every writer: what a command read (a shipped file found by its name, say) cannot
    be replaced by anything the command writes, however the path reaches it."""
    kept = tmp_path / "kept.json"
    kept.write_text('{"robots": [[0, 0]]}')
    link = tmp_path / "link.json"
    link.symlink_to(kept)
    with inputs_guarded():
        read_text(kept, 1000)
        for path in (kept, link):
            with pytest.raises(InputError, match="refusing to write over an input"):
                write_atomic(path, "lost")
    assert kept.read_text() == '{"robots": [[0, 0]]}'
    write_atomic(kept, "saved")  # outside a command (the visualiser's own Save): the user's choice
    assert kept.read_text() == "saved"


def test_an_output_through_a_symbolic_link_is_written_through_and_the_link_kept(tmp_path):
    target = tmp_path / "real.jsonl"
    target.write_text("old\n")
    link = tmp_path / "link.jsonl"
    link.symlink_to(target)
    out = run_cli("schedule", "--from-trace", str(TRACE), "--out", str(link), cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert "apf-viz-schedule" in target.read_text()


def fifo_input_commands(f: Path) -> list[list[str]]:
    return [
        ["run", "--robots", str(f), "--pattern", str(PATTERN)],
        ["run", "--robots", str(ROBOTS), "--pattern", str(f)],
        ["run", "--robots", str(ROBOTS), "--pattern", str(PATTERN), "--schedule", str(f)],
        ["replay", "--trace", str(f)],
        ["lecture", "check", str(f)],
        ["schedule", "--from-trace", str(f)],
        ["figure", "--trace", str(f)],
        ["export", "--trace", str(f), "--out", "x.html"],
        ["export", "--lecture", str(f), "--out", "x.html"],
        ["check", "--robots", str(f), "--pattern", str(PATTERN)],
        ["serve", "--trace", str(f), "--port", "0"],
    ]


def test_a_fifo_with_no_writer_as_an_input_is_refused_at_once(tmp_path):
    """Before, each of these waited for ever in open(); the timeout of run_cli fails the test instead."""
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    for command in fifo_input_commands(fifo):
        out = run_cli(*command, cwd=tmp_path)
        one_line_exit_2(out, "f: is a FIFO, not a regular file")
    assert not (tmp_path / "x.html").exists()


@pytest.mark.skipif(not Path("/proc/kmsg").exists(), reason="no /proc/kmsg here")
def test_a_file_that_claims_to_be_regular_but_would_wait_is_refused():
    """/proc/kmsg says it is a regular file, and a read waits for the kernel's next message: the read is
    non-blocking, so it is refused (or, unreadable, refused as such) instead of waiting for ever."""
    out = run_cli("run", "--robots", "/proc/kmsg", "--pattern", str(PATTERN), cwd=ROOT)
    # With kernel messages queued (an out-of-memory kill on the machine, say) the read returns them at
    # once, and they are refused as what they are: still one line, no wait.
    said = "/proc/kmsg: not valid JSON" if "not valid JSON" in out.stderr else "/proc/kmsg: cannot read"
    one_line_exit_2(out, said)
