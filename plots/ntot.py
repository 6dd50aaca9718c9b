#!/usr/bin/python3
"""The paper's Fig. ntot: collisions n_tot of a free-space collapse against k, from the JSON that
`granchain reproduce --figure fig10` writes.

Usage: /usr/bin/python3 plots/ntot.py fig10.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) N = 3: n_tot against log10 k; dashed through the last point, the slope of all collisions,
    -ln 10 / ln q(e) per decade of k (twice Eq. ntot-log: the paper's n counts the intervals of one
    pair, and each holds two collisions, docs/collapse.md); dotted, Eq. ntot-log itself,
    -ln 10 / (2 ln q);
(b) N = 25: log10 n_tot against log10 k. Error bars are one standard error.
"""
import sys

import numpy as np

from plot_common import PAGE, colours, figure, legend_axes, load, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig = figure(PAGE, 3.0, nrows=0)
    grid = fig.add_gridspec(2, 2, height_ratios=[1, 0.2])  # below (a): its legend
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])]
    three = [s for s in data["series"] if s["N"] == 3]
    others = [s for s in data["series"] if s["N"] != 3]
    for s, colour in zip(three, colours(len(three))):
        x = np.log10(np.array(s["k"]))
        n = np.array(s["n_tot"], dtype=float)
        err = np.array(s["error"], dtype=float)
        axes[0].errorbar(x, n, yerr=err, fmt="o", color=colour, label="$e = %g$" % s["e"])
        xx = np.array([x.min(), x.max()])
        if s.get("slope_per_decade") is not None:  # all collisions: 2 x Eq. ntot-log
            axes[0].plot(xx, n[-1] + s["slope_per_decade"] * (xx - x[-1]), "--", lw=0.8, color=colour)
        half = s.get("ntot_log_slope_per_decade")  # Eq. ntot-log as printed
        if half is not None:
            axes[0].plot(xx, n[-1] + half * (xx - x[-1]), ":", lw=0.8, color=colour)
    axes[0].plot([], [], "k--", lw=0.8, label=r"$-\ln k/\ln q$: all collisions, $2\times$Eq. ntot-log")
    if any(s.get("ntot_log_slope_per_decade") is not None for s in three):
        axes[0].plot([], [], "k:", lw=0.8, label=r"$-\ln k/(2\ln q)$: Eq. ntot-log")
    for s, colour in zip(others, colours(len(others) + 1)[1:]):
        x = np.log10(np.array(s["k"]))
        n = np.array(s["n_tot"], dtype=float)
        err = np.array(s["error"], dtype=float)
        axes[1].errorbar(x, np.log10(n), yerr=err / (n * np.log(10)), fmt="o-", color=colour,
                         label="$N = %d$, $e = %g$" % (s["N"], s["e"]))
    axes[0].set_xlabel(r"$\log_{10} k$")
    axes[0].set_ylabel(r"$n_{\rm tot}$")
    axes[0].set_title(r"(a) $N = 3$; lines through the last point", loc="left")
    axes[1].set_xlabel(r"$\log_{10} k$")
    axes[1].set_ylabel(r"$\log_{10} n_{\rm tot}$")
    axes[1].set_title(r"(b) $N = 25$", loc="left")
    handles, labels = axes[0].get_legend_handles_labels()
    legend_axes(fig.add_subplot(grid[1, :]), handles, labels, ncol=3, columnspacing=1.5)
    axes[1].legend(loc="upper left")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
