"""`apf-viz plot`: the figures of a sweep's results table (matplotlib, PNG).

- ``moves_vs_kD.png``: moves against k·D per algorithm (formed runs), the fitted constant c of
  moves ≈ c·k·D (least squares through the origin), and the line c·k·D;
- ``failure_rate.png``: the share of runs that did not form, per algorithm × scheduler × light semantics;
- ``events_per_move.png``: events per move against k, per algorithm (median over seeds);
- ``time_per_move.png``: wall time per move against k and D;
- ``worst_vs_kD.png``, where the table has runs of the searched adversary (scheduler ``worst-found``):
  for each start, the moves per k·D it found beside the most of the built-in schedulers' runs there.

The searched adversary's rows are no scheduler's run: the first four figures leave them out.
"""

from __future__ import annotations

import statistics
from collections.abc import Sequence
from pathlib import Path

from apf_viz.core.files import replace_atomically
from apf_viz.core.formats import InputError
from apf_viz.sweeps.cells import WORST_FOUND

FIGURES = ("moves_vs_kD.png", "failure_rate.png", "events_per_move.png", "time_per_move.png")


def _save(fig, path: Path) -> None:
    replace_atomically(
        path, lambda tmp: fig.savefig(tmp, dpi=120, bbox_inches="tight"), ".png", through_links=False
    )


def _finish(fig, ax, path: Path, xlabel: str, ylabel: str, title: str) -> Path:
    """Labels, legend and grid of a line or scatter figure; then written and closed."""
    import matplotlib.pyplot as plt

    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    _save(fig, path)
    plt.close(fig)
    return path


def fitted_constant(points: Sequence[tuple[float, float]]) -> float:
    """c minimising Σ (y − c·x)²: the constant of y ≈ c·x."""
    sxx = sum(x * x for x, _ in points)
    return sum(x * y for x, y in points) / sxx if sxx else 0.0


def plot(rows: Sequence[dict], out: Path) -> list[Path]:
    if not rows:
        raise InputError("the results table has no rows")
    searched = [r for r in rows if r["scheduler"] == WORST_FOUND]
    rows = [r for r in rows if r["scheduler"] != WORST_FOUND]
    if not rows:
        raise InputError("the results table has only the searched adversary's rows: no scheduler to compare")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    algorithms = sorted({r["algorithm"] for r in rows})
    written = [_moves_vs_kd(rows, algorithms, out / FIGURES[0])]

    groups: dict[str, list[dict]] = {}
    for r in rows:
        groups.setdefault(f"{r['algorithm']}\n{r['scheduler']}, {r['light_semantics']}", []).append(r)
    names = sorted(groups)
    rates = [100 * sum(r["outcome"] != "formed" for r in groups[n]) / len(groups[n]) for n in names]
    fig, ax = plt.subplots(figsize=(max(6, 1.6 * len(names)), 4.5))
    bars = ax.bar(range(len(names)), rates, color="#c44")
    for bar, n in zip(bars, names, strict=True):
        ax.annotate(f"{len(groups[n])} runs", (bar.get_x() + bar.get_width() / 2, bar.get_height()),
                    ha="center", va="bottom", fontsize=7)  # fmt: skip
    ax.set_xticks(range(len(names)), names, fontsize=7)
    ax.set_ylabel("runs that did not form (%)")
    ax.set_ylim(0, max(100, max(rates) + 5))
    ax.set_title("Failure rate by algorithm × scheduler × light semantics")
    written.append(out / FIGURES[1])
    _save(fig, written[-1])
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for alg in algorithms:
        by_k: dict[int, list[float]] = {}
        for r in rows:
            if r["algorithm"] == alg and r["moves"] > 0:
                by_k.setdefault(r["k"], []).append(r["events"] / r["moves"])
        ks = sorted(by_k)
        if ks:
            ax.plot(ks, [statistics.median(by_k[k]) for k in ks], marker="o", label=alg)
    ylabel = "events per move (median over runs)"
    written.append(_finish(fig, ax, out / FIGURES[2], "k (robots)", ylabel, "Events per move against k"))
    written.append(_time_per_move(rows, algorithms, out / FIGURES[3]))
    if searched:
        written.append(_worst_vs_kd(searched, rows, out / WORST_FIGURE))
    return written


WORST_FIGURE = "worst_vs_kD.png"


def _start_of(r: dict) -> tuple:
    return (r["k"], r["seed"], r["algorithm"], r["light_semantics"], r["start"])


def worst_against_built_ins(searched: Sequence[dict], rows: Sequence[dict]) -> list[tuple[int, float, float]]:
    """For each start the searched adversary ran on and some built-in scheduler formed: (k·D, the moves
    per k·D it found, the most of the built-in runs' there), in the order of k·D."""
    most: dict[tuple, float] = {}
    for r in rows:
        if r["outcome"] == "formed":
            most[_start_of(r)] = max(most.get(_start_of(r), 0.0), r["moves_per_kD"])
    return sorted(
        (r["k"] * r["D"], r["moves_per_kD"], most[_start_of(r)])
        for r in searched
        if r["outcome"] == "formed" and _start_of(r) in most
    )


def _worst_vs_kd(searched: Sequence[dict], rows: Sequence[dict], path: Path) -> Path:
    import matplotlib.pyplot as plt

    pts = worst_against_built_ins(searched, rows)
    if not pts:
        raise InputError("no start has both a run of the searched adversary and a built-in run that formed")
    fig, ax = plt.subplots(figsize=(7, 4.5))
    x = [p[0] for p in pts]
    ax.scatter(
        x, [p[2] for p in pts], s=22, marker="o", label="the built-in schedulers in the table: their most"
    )
    ax.scatter(x, [p[1] for p in pts], s=22, marker="x", label="the searched adversary (worst found)")
    ax.set_ylim(bottom=0)
    title = "The worst found against the built-in schedulers: moves per k·D on each start"
    return _finish(fig, ax, path, "k · D  (D = max(m, n, M, N, k))", "moves / (k·D)", title)


def _moves_vs_kd(rows: Sequence[dict], algorithms: list[str], path: Path) -> Path:
    """Moves against k·D per algorithm (formed runs), with the fitted c·k·D."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    top = 0.0
    for alg in algorithms:
        pts = [
            (r["k"] * r["D"], r["moves"]) for r in rows if r["algorithm"] == alg and r["outcome"] == "formed"
        ]
        if not pts:
            continue
        c = fitted_constant(pts)
        top = max(top, max(x for x, _ in pts))
        ax.scatter([x for x, _ in pts], [y for _, y in pts], s=14, alpha=0.6, label=f"{alg} (c = {c:.2f})")
        ax.plot([0, top], [0, c * top], linewidth=1)
    title = "Moves against k·D: the paper's O(kD) bound, fitted moves ≈ c·k·D"
    return _finish(fig, ax, path, "k · D  (D = max(m, n, M, N, k))", "moves until formed", title)


def _time_per_move(rows: Sequence[dict], algorithms: list[str], path: Path) -> Path:
    """Wall time per move against k and against D, one point per run that moved: what a move costs,
    whether it grows with the robots a mover sees or with the distances between them."""
    import matplotlib.pyplot as plt

    fig, (by_k, by_d) = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for alg in algorithms:
        runs = [r for r in rows if r["algorithm"] == alg and r["moves"] > 0 and r["wall_s"] > 0]
        if not runs:
            continue
        per_move = [1e6 * r["wall_s"] / r["moves"] for r in runs]
        by_k.scatter([r["k"] for r in runs], per_move, s=14, alpha=0.6, label=alg)
        by_d.scatter([r["D"] for r in runs], per_move, s=14, alpha=0.6, label=alg)
    for ax, label in ((by_k, "k (robots)"), (by_d, "D = max(m, n, M, N, k)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(label)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    by_k.set_ylabel("wall time per move (µs)")
    fig.suptitle("Time per move against k and against D (each point one run)")
    _save(fig, path)
    plt.close(fig)
    return path


LIGHTS_FIGURE = "light_merges.png"
_VERDICT_COLOURS = {
    "breaks": "#d9534f",
    "survives": "#5cb85c",
    "untested": "#5b7fbf",
    "inconclusive": "#f0ad4e",
    "error": "#999999",
}


def _merge_label(r: dict) -> str:
    """A merge's cell: the violation and the robots of its counterexample, a tick, or the verdict."""
    if r["verdict"] == "breaks":
        return f"{r['violation'].split(':')[0]}\nk={r['k']}" + (" (rnd)" if r["stage"] == "random" else "")
    if r["verdict"] == "survives":
        return "✓" + (f"\n{r['random_runs']} rnd" if r["random_runs"] else "")
    return r["verdict"]


def plot_lights(rows: Sequence[dict], out: Path) -> Path:
    """The matrix of merges of ``apf-viz lights``: row a, column b is ``merge(a=b)`` (b shown as a);
    red breaks (marked with the violation's initial and the robots of the counterexample), green survives
    (its merge at work somewhere), blue untested (never at work: nothing is claimed), grey not run. One
    figure per table (the first algorithm and --ks if it holds several)."""
    if not rows:
        raise InputError("the lights table has no rows")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    from apf_viz.algorithms import get_algorithm

    first = rows[0]
    rows = [r for r in rows if (r["algorithm"], r["ks"]) == (first["algorithm"], first["ks"])]
    lights = list(get_algorithm(first["algorithm"]).lights)
    cell = {(r["shown"], r["hidden"]): r for r in rows}
    n = len(lights)
    fig, ax = plt.subplots(figsize=(1.0 * n + 3, 0.8 * n + 2))
    for i, a in enumerate(lights):
        for j, b in enumerate(lights):
            r = cell.get((a, b))
            colour = "#333333" if a == b else _VERDICT_COLOURS.get(r["verdict"], "#999") if r else "#e6e6e6"
            ax.add_patch(plt.Rectangle((j, i), 1, 1, facecolor=colour, edgecolor="white", linewidth=2))
            if r is not None and a != b:
                ax.text(
                    j + 0.5, i + 0.5, _merge_label(r), ha="center", va="center", fontsize=7, color="white"
                )
    ax.set_xlim(0, n)
    ax.set_ylim(n, 0)
    ax.set_xticks([j + 0.5 for j in range(n)], lights, rotation=40, ha="right", fontsize=8)
    ax.set_yticks([i + 0.5 for i in range(n)], lights, fontsize=8)
    ax.set_xlabel("b: the light that disappears (shown as a)")
    ax.set_ylabel("a: the colour both show")
    ax.set_aspect("equal")
    counts = {v: sum(r["verdict"] == v for r in rows) for v in _VERDICT_COLOURS}
    ax.legend(
        handles=[
            Patch(color=c, label=f"{v} ({counts[v]})") for v, c in _VERDICT_COLOURS.items() if counts[v]
        ],
        loc="upper left",
        bbox_to_anchor=(1.02, 1),
        fontsize=8,
    )
    runs = max((r["random_runs"] for r in rows), default=0)
    ax.set_title(
        f"{first['algorithm']}+merge(a=b): is light b needed?\nexplorer on k = {first['ks']} "
        "(symmetric starts with robots on the axis in a 5×5 box, k ≤ 3: every start of a 4×4 box; "
        "4–5: the stated starts), every flip assignment"
        + (f"; survivors: {runs} random runs (rnd)" if runs else ""),
        fontsize=9,
    )
    out.mkdir(parents=True, exist_ok=True)
    path = out / LIGHTS_FIGURE
    _save(fig, path)
    plt.close(fig)
    return path
