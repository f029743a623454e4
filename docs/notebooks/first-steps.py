# %% [markdown]
# # First steps with apf-viz from Python
#
# A run, its events as a table, a sweep of 100 runs into a DataFrame and a plot of moves against k·D,
# a counterexample found, checked and replayed, and a run shown in the notebook. Needs the `notebook`
# extra: `pip install -e '.[notebook]'` in a checkout. (This file is a notebook in the percent format:
# Jupyter opens it with jupytext; VS Code and PyCharm run its cells as they are. tests/test_api.py runs
# it top to bottom. Not as `python first-steps.py`: the sweep's worker processes would import the
# script that started them, and so run it again; a notebook's kernel has no such script.)

# %%
import apf_viz

r = apf_viz.run("sym-call-7", "cup-7", scheduler="async", seed=3)
r

# %% [markdown]
# Every event of the run: who acted, which phase, the rule a Compute fired, the light after it, where
# the robot stands.

# %%
events = r.events_table()
events.head(12)

# %%
events.groupby("phase").size()

# %% [markdown]
# ## 100 runs
#
# Four robot counts, 25 seeds each, under ASYNC: the starts `apf-viz sweep` draws for each (k, seed)
# (docs/SWEEPS.md), on this machine's cores.

# %%
table = apf_viz.sweep(ks=[4, 6, 8, 10], seeds=range(25), schedulers=["async"])
table["kD"] = table["k"] * table["D"]
table.groupby("k")[["moves", "moves_per_kD"]].describe()

# %% [markdown]
# The paper's bound is O(kD) moves: the moves of every run against k·D.

# %%
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(6, 4))
formed = table[table["outcome"] == "formed"]
ax.scatter(formed["kD"], formed["moves"], s=12, label="formed")
others = table[table["outcome"] != "formed"]
if len(others):
    ax.scatter(others["kD"], others["moves"], s=16, marker="x", color="red", label="not formed")
ax.set_xlabel("k·D")
ax.set_ylabel("moves")
ax.set_title(f"{len(table)} runs, ASYNC: at most {table['moves_per_kD'].max():.2f}·k·D moves")
ax.legend()
fig.savefig("moves-against-kD.png", dpi=100)

# %% [markdown]
# ## A counterexample
#
# The paper's algorithm as written collides under ASYNC on this start of four robots (docs/ALGORITHM.md):
# every schedule and every assignment of the robots' y-axes is explored, and the first failure returned.

# %%
v = apf_viz.check(
    [(0, 0), (0, 1), (0, 2), (0, 4)],
    [(0, 1), (1, 1), (2, 1), (1, 0)],
    algorithm="apf-opaque-grid-literal",
    flips="all",
)
print(v.verdict, f"after {len(v.schedule)} steps;", v.detail)

# %% [markdown]
# Replayed by the real engine, event for event:

# %%
bad = v.replay()
assert bad.outcome == "collision"
bad.events_table().tail(4)

# %% [markdown]
# ## The run, shown
#
# The page `apf-viz export` writes (viser's own player), in this cell.

# %%
r.show()
