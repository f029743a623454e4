"""Commands say what they will write and how long they will take, before they start; an ETA that moves;
the same seeds everywhere; an unknown option names its command."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz.lights.driver import _progress_line


def apf_viz(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True, cwd=cwd, timeout=600
    )


def test_the_lights_lab_names_every_file_it_writes_on_its_first_line_and_bounds_its_time(tmp_path):
    done = apf_viz("lights", "--ks", "1-2", "--merges", "off=call,leader1=decider", "--out", "l.parquet",
                   "--workers", "1", cwd=tmp_path)  # fmt: skip
    assert done.returncode == 0, done.stderr
    lines = done.stderr.splitlines()
    first = lines[0]
    assert first.startswith("apf-viz lights: 2 merges") and "stage 0 first" in first
    written = sorted(p.name for p in tmp_path.iterdir())
    assert written == ["l-base.json", "l-traces", "l.parquet"] or written == ["l-base.json", "l.parquet"]
    for name in ("l.parquet", "l-base.json", "l-traces/"):
        assert name in first  # said before any work, not only at the end
    bound = next(line for line in lines if "merges to explore" in line)
    assert "at most about" in bound
    again = apf_viz("lights", "--ks", "1-2", "--merges", "off=call,leader1=decider", "--out", "l.parquet",
                    "--workers", "1", cwd=tmp_path)  # fmt: skip
    assert "stage 0 kept from an earlier run" in again.stderr.splitlines()[0]


def test_the_labs_eta_counts_down_while_no_merge_finishes_and_says_when_it_is_over():
    one = [{"verdict": "breaks"}]
    at_30 = _progress_line(one, 3, 30.0, 100.0)
    at_40 = _progress_line(one, 3, 40.0, 100.0)
    assert "ETA at most about 70 s" in at_30 and "ETA at most about 60 s" in at_40  # it moves
    assert "over the estimate by 30 s" in _progress_line(one, 3, 130.0, 100.0)
    assert _progress_line(one * 3, 3, 50.0, 100.0).endswith("ETA done")


def test_plot_says_where_it_writes_before_it_writes(tmp_path):
    out = tmp_path / "r.csv"
    assert apf_viz("sweep", "--ks", "3", "--seeds", "1", "--workers", "1", "--out", str(out),
                   cwd=tmp_path).returncode == 0  # fmt: skip
    done = apf_viz("plot", str(out), cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stderr.splitlines()[0] == "apf-viz plot: writing PNGs into plots/"
    assert (tmp_path / "plots").is_dir()


@pytest.mark.parametrize(
    "argv",
    [
        ["run", "--robots", "sym-call-7", "--pattern", "cup-7", "--seed", "-1"],
        ["check", "--robots", "sym-call-7", "--pattern", "cup-7", "--seed", "-1"],
        ["random-robots", "--count", "3", "--width", "4", "--height", "4", "--seed", "-2"],
        ["sweep", "--ks", "3", "--seeds=-3", "--out", "x.csv"],
    ],
)
def test_seeds_are_0_or_more_for_every_command(tmp_path, argv):
    done = apf_viz(*argv, cwd=tmp_path)
    assert done.returncode == 2
    (line,) = done.stderr.strip().splitlines()[-1:]
    assert "seed" in line and ("0 or more" in line)


@pytest.mark.parametrize(
    "argv",
    [
        ["run", "--robots", "sym-call-7", "--pattern", "cup-7"],
        ["sweep", "--out", "x.csv"],
        ["serve"],
        ["lights", "--out", "l.parquet"],
    ],
)
def test_an_unknown_option_is_named_with_its_command(tmp_path, argv):
    done = apf_viz(*argv, "--no-such-option", cwd=tmp_path)
    assert done.returncode == 2
    command = argv[0]
    assert done.stderr.strip().splitlines() == [
        f"apf-viz {command}: error: unrecognized arguments: --no-such-option (see apf-viz {command} --help)"
    ]
    assert not list(tmp_path.iterdir())  # refused before any work
