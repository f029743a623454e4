# %% [markdown]
# # The adversary's notebook
#
# A start of your own; the most moves any schedule can force on it, exactly, and the schedule that
# forces it, shown; the searched adversary against it; every flip of the y-axes; and a hunt over
# generated starts, summarised. Needs the `notebook` extra: `pip install -e '.[notebook]'` in a checkout.
# (A notebook in the percent format, as first-steps.py; tests/test_api_workflow.py runs it top to
# bottom.)

# %%
import json

import apf_viz

# Four robots packed together and one far below them (the "packed-far" family's start of seed 2).
start = {"robots": [[1, 2], [3, 2], [1, 0], [2, 2], [1, 8]], "y_up": [True, False, True, True, False]}
with open("mine.robots.json", "w") as f:
    json.dump(start, f)
pattern = [(1, 0), (1, 3), (2, 2), (3, 0), (2, 3)]
r = apf_viz.run("mine.robots.json", pattern, seed=1)
r

# %% [markdown]
# ## The exact worst
#
# Every ASYNC schedule of this start, explored: the most moves an adversary can force before the
# pattern forms, and one schedule forcing it (replayed by the real engine to the same count before it
# is returned).

# %%
worst = apf_viz.check("mine.robots.json", pattern, worst="moves")
print(worst)
print(
    f"worst {worst.value} moves ({worst.per_kD:.3f} per k·D); seed 1's run: {r.moves} ({r.moves_per_kD:.3f})"
)

# %%
forced = worst.replay()
assert forced.moves == worst.value
worst.save_schedule("worst.schedule")  # apf-viz run --schedule worst.schedule replays it too
forced.show()

# %% [markdown]
# ## The searched adversary
#
# What `apf-viz adversary` finds without exploring every schedule: the built-in schedulers' runs set the
# bar, then beams and variants of the costliest schedules. On a start this small a beam is never cut, so
# the search knows it has the exact worst.

# %%
found = apf_viz.adversary("mine.robots.json", pattern, budget=50)
print(found)
assert found.count <= worst.value
print(
    f"the built-in schedulers' most: {found.built_ins} moves; the search: {found.count}; exact: {worst.value}"
)

# %% [markdown]
# ## Every flip
#
# The robots' y-axes are the adversary's too: every one of the 2^5 assignments.

# %%
every = apf_viz.check("mine.robots.json", pattern, worst="moves", flips="all")
print(every.value, every.y_up, f"{every.per_kD:.3f} per k·D")
assert every.value >= worst.value

# %% [markdown]
# ## A hunt
#
# Twenty-four generated starts of 5–7 robots, three of each family, every schedule of each explored:
# verified, or the failure and its counterexample.

# %%
hunted = apf_viz.hunt(ks=range(5, 8), count=24, seed=7)
hunted.groupby("family")[["states", "seconds"]].agg(["count", "mean", "max"])

# %%
hunted["verdict"].value_counts()
