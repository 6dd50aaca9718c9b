#!/usr/bin/python3
"""The paper's Fig. logfitbX from `granchain reproduce --figure fig7` (fig7.json).

Usage: /usr/bin/python3 plots/scaling_collapse.py fig7.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) b/N^(5/2) against X = (1 - e) - 2.6/N (log-log), the paper's 1.5 X^2 dashed and the fit of
this data solid; (b) the same with the A fitted to this data's e_c1; (c) b/N^(1/2) against N(1 - e).
b is the slope of n_coll per decade of k in the logarithmically collapsing regime; error bars are
one standard error.
"""
import sys

import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from plot_common import PAGE, colours, figure, legend_axes, load, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    pts = data["points"]
    fig = figure(PAGE, 2.9, nrows=0)
    grid = fig.add_gridspec(2, 3, height_ratios=[1, 0.1])
    axes = [fig.add_subplot(grid[0, i]) for i in range(3)]
    Ns = sorted({p["N"] for p in pts})
    colors = dict(zip(Ns, colours(len(Ns))))
    for ax, fit in zip(axes[:2], data["fits"] + [None] * (2 - len(data["fits"]))):
        if fit is None:  # no A of this data (too few e_c1 across N): say so rather than leave a hole
            ax.text(0.5, 0.5, "(b) no fit of A from this data\n(fewer than two N with an $e_{c1}$)", ha="center",
                    va="center", transform=ax.transAxes)
            ax.set_xticks([])
            ax.set_yticks([])
            continue
        A = fit["A"]
        xs = []
        for N in Ns:
            sel = [p for p in pts if p["N"] == N and (1 - p["e"]) - A / N > 0 and p["b"] > 0]
            if not sel:
                continue
            X = np.array([(1 - p["e"]) - A / N for p in sel])
            y = np.array([p["b"] for p in sel]) / N ** 2.5
            err = np.array([p["b_err"] for p in sel]) / N ** 2.5
            xs.extend(X)
            ax.errorbar(X, y, yerr=np.minimum(err, 0.99 * y), fmt="o", ms=2.5, color=colors[N], label="$N = %d$" % N)
        if xs:
            xx = np.geomspace(min(xs), max(xs), 50)
            ax.plot(xx, 1.5 * xx ** 2, "k--", lw=0.8, label=r"paper: $1.5 X^2$")
            if "slope" in fit:
                ax.plot(xx, fit["prefactor"] * xx ** fit["slope"], "k-", lw=0.8,
                        label=r"fit: $%.2f X^{%.2f}$" % (fit["prefactor"], fit["slope"]))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"$X = (1 - e) - %.2f/N$" % A)
        ax.set_ylabel(r"$b / N^{5/2}$")
        # X spans about one decade: labels at 1, 2 and 5 times each power of ten, written as decimals.
        ax.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: "%g" % v))
        ax.xaxis.set_minor_formatter(NullFormatter())
        lines = [h for h, l in zip(*ax.get_legend_handles_labels()) if not l.startswith("$N")]
        ax.legend(lines, [l.get_label() for l in lines], loc="lower right")
        ax.set_title("(%s) %s" % ("a" if ax is axes[0] else "b", fit["name"]), loc="left")
    ax = axes[2]
    for N in Ns:
        sel = [p for p in pts if p["N"] == N]
        ax.errorbar([N * (1 - p["e"]) for p in sel], [p["b"] / N ** 0.5 for p in sel],
                    yerr=[p["b_err"] / N ** 0.5 for p in sel], fmt="o", ms=2.5, color=colors[N], label="$N = %d$" % N)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel(r"$N (1 - e)$")
    ax.set_ylabel(r"$b / N^{1/2}$")
    # One legend of N for the three panels, below them.
    handles, labels = ax.get_legend_handles_labels()
    legend_axes(fig.add_subplot(grid[1, :]), handles, labels, ncol=len(labels))
    ax.set_title("(c) linear scale", loc="left")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
