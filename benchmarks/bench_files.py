"""Reading big input files: a schedule of a million lines (time and peak memory of ``load_schedule``,
each in a child process so that its peak is its own), and a refused device file (``/dev/zero`` as a
robots file: read up to the limit, then refused).

Run: python benchmarks/bench_files.py [--lines 1000000]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

MEASURE = """
import json, resource, sys, time
from apf_viz.core import engine  # imported by any run anyway: not counted
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
from apf_viz.core.schedule import load_schedule
from apf_viz.core.formats import InputError, load_robots
t = time.perf_counter()
if sys.argv[1] == "schedule":
    n = len(load_schedule(sys.argv[2]))
else:
    try:
        load_robots(sys.argv[2])
    except InputError:
        n = 0
dt = time.perf_counter() - t
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(json.dumps({"lines": n, "seconds": dt, "peak_mib": peak / 1024, "above_mib": (peak - base) / 1024}))
"""


def write_schedule(path: Path, lines: int) -> None:
    phases = ("look", "compute", "move")
    with path.open("w") as f:
        f.write(json.dumps({"format": "apf-viz-schedule", "version": 2, "robots": 10, "y_up": [True] * 10}))
        f.write("\n")
        for i in range(lines):
            f.write(json.dumps({"robot": i % 10, "phase": phases[i % 3]}) + "\n")


def measure(kind: str, path: str) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", MEASURE, kind, path], capture_output=True, text=True, check=True
    )
    return json.loads(out.stdout)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    ap.add_argument("--lines", type=int, default=1_000_000, help="lines of the generated schedule")
    args = ap.parse_args()
    print("| input | size | read in | peak memory (above the imports) |")
    print("|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "schedule.jsonl"
        write_schedule(path, args.lines)
        r = measure("schedule", str(path))
        size = path.stat().st_size / 1e6
        print(
            f"| schedule, {r['lines']:,} lines | {size:.0f} MB | {r['seconds']:.1f} s "
            f"| {r['above_mib']:.0f} MiB |"
        )
    if Path("/dev/zero").exists():
        r = measure("robots", "/dev/zero")
        print(
            f"| /dev/zero as a robots file (refused) | endless | {r['seconds']:.2f} s "
            f"| {r['above_mib']:.0f} MiB |"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
