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

from plot_common import load, plt, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    pts = data["points"]
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.5))
    Ns = sorted({p["N"] for p in pts})
    colors = {N: plt.cm.viridis(i / max(1, len(Ns) - 1)) for i, N in enumerate(Ns)}
    for ax, fit in zip(axes[:2], data["fits"] + [None] * (2 - len(data["fits"]))):
        if fit is None:  # no A of this data (too few e_c1 across N): say so rather than leave a hole
            ax.text(0.5, 0.5, "(b) no fit of A from this data\n(fewer than two N with an $e_{c1}$)", ha="center",
                    va="center", transform=ax.transAxes, fontsize=10)
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
            ax.errorbar(X, y, yerr=np.minimum(err, 0.99 * y), fmt="o", ms=3, capsize=2, color=colors[N], label="$N = %d$" % N)
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
        ax.legend(fontsize=8)
        ax.set_title("(%s) %s" % ("a" if ax is axes[0] else "b", fit["name"]), fontsize=10)
    ax = axes[2]
    for N in Ns:
        sel = [p for p in pts if p["N"] == N]
        ax.errorbar([N * (1 - p["e"]) for p in sel], [p["b"] / N ** 0.5 for p in sel],
                    yerr=[p["b_err"] / N ** 0.5 for p in sel], fmt="o", ms=3, capsize=2, color=colors[N], label="$N = %d$" % N)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel(r"$N (1 - e)$")
    ax.set_ylabel(r"$b / N^{1/2}$")
    ax.legend(fontsize=8)
    ax.set_title("(c) linear scale", fontsize=10)
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
