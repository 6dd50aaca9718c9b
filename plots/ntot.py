#!/usr/bin/python3
"""The paper's Fig. ntot: collisions n_tot of a free-space collapse against k, from the JSON that
`granchain reproduce --figure fig10` writes.

Usage: /usr/bin/python3 plots/ntot.py fig10.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) N = 3: n_tot against log10 k, with lines of the predicted slope of all collisions
    (-ln 10 / ln q(e) per decade; twice Eq. ntot-log, docs/collapse.md) through the last point;
(b) N = 25: log10 n_tot against log10 k. Error bars are one standard error.
"""
import sys

import numpy as np

from plot_common import load, plt, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for s in data["series"]:
        x = np.log10(np.array(s["k"]))
        n = np.array(s["n_tot"], dtype=float)
        err = np.array(s["error"], dtype=float)
        if s["N"] == 3:
            line = axes[0].errorbar(x, n, yerr=err, fmt="o", ms=3, capsize=2, label="$e = %g$" % s["e"])
            if s.get("slope_per_decade") is not None:
                xx = np.array([x.min(), x.max()])
                axes[0].plot(xx, n[-1] + s["slope_per_decade"] * (xx - x[-1]), "--", lw=0.8,
                             color=line[0].get_color())
        else:
            axes[1].errorbar(x, np.log10(n), yerr=err / (n * np.log(10)), fmt="o-", ms=3, lw=0.8, capsize=2,
                             label="$N = %d$, $e = %g$" % (s["N"], s["e"]))
    axes[0].set_xlabel(r"$\log_{10} k$")
    axes[0].set_ylabel(r"$n_{\rm tot}$")
    axes[0].set_title(r"(a) $N = 3$ (dashed: predicted slope)", fontsize=10)
    axes[1].set_xlabel(r"$\log_{10} k$")
    axes[1].set_ylabel(r"$\log_{10} n_{\rm tot}$")
    axes[1].set_title(r"(b) $N = 25$", fontsize=10)
    for ax in axes:
        ax.legend(fontsize=8)
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
