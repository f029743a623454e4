"""`apf-viz lights`: the light-budget lab. Which of an algorithm's lights could be one colour?

Every ordered pair (a, b) of the algorithm's lights names a variant ``ALG+merge(a=b)``: b is shown as a,
to every robot including itself (docs/ALGORITHM.md, "Variants"). Each merge is put to two tests:

0. **the base algorithm** is explored first on every start stage 1 uses: a start on which it fails
   itself cannot tell a merge's failure from its own, and is left out (and said).
1. **the explorer** (ASYNC, partial-order reduction): for each k, every start of k ≤ 5 robots in a 5×5
   box that is symmetric with robots on its axis (the hardest for leader election), then every solvable
   start of k ≤ 3 in a 4×4 box up to translation and mirror, then the stated k = 4–5 starts
   (:data:`STATED_STARTS`), each under every assignment of y-axis flips, towards a row of k points. The
   first violation ends the merge's search; its shortest schedule is kept as a trace.
2. **random adversarial runs** for the merges the explorer could not break: N runs under every scheduler
   (fsync, ssync, async, stale-first, round-robin), a third on random starts of k = 6–12, a third on
   random symmetric starts of 8–20 robots with robots on the axis, a third on the Demo scenarios' starts
   scaled ×1, ×2 and ×3, through the sweep machinery (``apf-viz sweep``'s Dask cluster, results file,
   resume and progress).

**Coverage before verdict.** A merge can only change a run where the base algorithm sets the hidden
light (it then shows the merged colour): the lab counts those decisions (``merged_lights.AtWork``) in
the explorer and in the random runs, each distinct view once per start (or per run), probes
included: a merge can turn a decision into "same light, stay", and then no Compute ever shows it. A
merge that breaks nowhere *and was never at work* is ``untested``, never ``survives``; one that was at
work and broke nowhere ``survives`` with its counts: evidence, not a proof.

One Dask task per merge. Rows are written atomically as merges finish; the same command resumes, skipping
the merges already in the file; Ctrl+C keeps what finished.
"""

from apf_viz.lights.driver import base_path as base_path
from apf_viz.lights.driver import base_verified_starts as base_verified_starts
from apf_viz.lights.driver import kept_base as kept_base
from apf_viz.lights.driver import random_path as random_path
from apf_viz.lights.driver import report_progress as report_progress
from apf_viz.lights.driver import run_lab as run_lab
from apf_viz.lights.merges import COLUMNS as COLUMNS
from apf_viz.lights.merges import DEMO_SCALES as DEMO_SCALES
from apf_viz.lights.merges import KEY as KEY
from apf_viz.lights.merges import MAX_STATES as MAX_STATES
from apf_viz.lights.merges import RANDOM_KS as RANDOM_KS
from apf_viz.lights.merges import RANDOM_SCHEDULERS as RANDOM_SCHEDULERS
from apf_viz.lights.merges import RANDOM_SYMMETRIC_KS as RANDOM_SYMMETRIC_KS
from apf_viz.lights.merges import Merge as Merge
from apf_viz.lights.merges import explore_every_flip as explore_every_flip
from apf_viz.lights.merges import ks_label as ks_label
from apf_viz.lights.merges import merges as merges
from apf_viz.lights.merges import parse_ks as parse_ks
from apf_viz.lights.merges import starts_for as starts_for
from apf_viz.lights.stages import MAX_RANDOM_RUNS as MAX_RANDOM_RUNS
from apf_viz.lights.stages import demo_starts as demo_starts
from apf_viz.lights.stages import explore_merge as explore_merge
from apf_viz.lights.stages import fold_random as fold_random
from apf_viz.lights.stages import random_cells as random_cells
from apf_viz.lights.stages import verdict_row as verdict_row
from apf_viz.lights.stages import verify_start as verify_start
from apf_viz.lights.stories import story as story
from apf_viz.lights.table import is_lights_table as is_lights_table
from apf_viz.lights.table import read_lights as read_lights
from apf_viz.lights.table import summary as summary
from apf_viz.lights.table import write_lights as write_lights

__all__ = [
    "COLUMNS",
    "DEMO_SCALES",
    "KEY",
    "MAX_RANDOM_RUNS",
    "MAX_STATES",
    "RANDOM_KS",
    "RANDOM_SCHEDULERS",
    "RANDOM_SYMMETRIC_KS",
    "Merge",
    "base_path",
    "base_verified_starts",
    "demo_starts",
    "explore_every_flip",
    "explore_merge",
    "fold_random",
    "is_lights_table",
    "kept_base",
    "ks_label",
    "merges",
    "parse_ks",
    "random_cells",
    "random_path",
    "read_lights",
    "report_progress",
    "run_lab",
    "starts_for",
    "story",
    "summary",
    "verdict_row",
    "verify_start",
    "write_lights",
]
