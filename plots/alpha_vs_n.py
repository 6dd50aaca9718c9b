#!/usr/bin/python3
"""The paper's Fig. powerexpo from `granchain reproduce --figure fig9` (fig9.json).

Usage: /usr/bin/python3 plots/alpha_vs_n.py fig9.json PREFIX   -> PREFIX.png and PREFIX.pdf
The exponent alpha of n_coll ~ k^alpha at e = 0.1, 0.2, 0.3, 0.4 against log10 N (one standard
error), the mean over the four e, its linear fit (solid) and the paper's 0.18 log10 N - 0.054
(dashed, Eq. alphafit); beside it (b) the local exponent per interval of k, mean over the four e,
against log10 N, one line per interval: a power law would put them on top of each other.
"""
import sys

import numpy as np

from plot_common import PAGE, SEQUENTIAL_2, figure, load, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig, (ax, bx) = figure(PAGE, 2.9, ncols=2)
    markers = {0.1: "o", 0.2: "s", 0.3: "^", 0.4: "v"}
    logs = []
    for e, m in markers.items():
        x, y, err = [], [], []
        for f in data["families"]:
            for a in f["alphas"]:
                if abs(a["e"] - e) < 1e-9:
                    x.append(np.log10(f["N"]) + (e - 0.25) * 0.02)  # small offsets keep the bars apart
                    y.append(a["alpha"])
                    err.append(a["error"])
        if x:
            ax.errorbar(x, y, yerr=err, fmt=m, ms=3, mfc="none", label="$e = %g$" % e)
    for f in data["families"]:
        logs.append(np.log10(f["N"]))
        if f["alpha_bar"]:
            ax.errorbar(np.log10(f["N"]), f["alpha_bar"]["value"], yerr=f["alpha_bar"]["error"], fmt="D", color="k", ms=3)
    ax.plot([], [], "D", color="k", label=r"mean ($\bar\alpha$)")
    if logs:
        xx = np.linspace(min(logs) - 0.05, max(logs) + 0.05, 20)
        ax.plot(xx, 0.18 * xx - 0.054, "k--", lw=0.8, label=r"paper: $0.18 \log_{10} N - 0.054$")
        if data.get("fit"):
            ax.plot(xx, data["fit"]["slope"] * xx + data["fit"]["intercept"], "k-", lw=0.8,
                    label=r"fit: $%.3f \log_{10} N %+.3f$" % (data["fit"]["slope"], data["fit"]["intercept"]))
    ax.set_xlabel(r"$\log_{10} N$")
    ax.set_ylabel(r"$\alpha$")
    ax.set_title("(a) global fits", loc="left")
    ax.legend(loc="best")  # wherever it covers the fewest points: the columns shown vary by preset
    # (b) local exponents per interval of k
    intervals = sorted({(l["k1"], l["k2"]) for f in data["families"] for l in f.get("local_alpha_bar", [])})
    cmap = SEQUENTIAL_2
    for i, (k1, k2) in enumerate(intervals):
        pts = sorted((np.log10(f["N"]), l["alpha"], l["error"]) for f in data["families"]
                     for l in f.get("local_alpha_bar", []) if (l["k1"], l["k2"]) == (k1, k2))
        if pts:
            x, y, err = (np.array(v) for v in zip(*pts))
            bx.errorbar(x, y, yerr=err, fmt="o-", ms=2.5, lw=0.8, color=cmap(i / max(1, len(intervals) - 1)),
                        label=r"$k = 10^{%d} \ldots 10^{%d}$" % (round(np.log10(k1)), round(np.log10(k2))))
    if logs:
        bx.plot(xx, 0.18 * xx - 0.054, "k--", lw=0.8, label=r"paper: $0.18 \log_{10} N - 0.054$")
    bx.set_xlabel(r"$\log_{10} N$")
    bx.set_ylabel(r"local $\alpha$, mean over $e = 0.1, \ldots, 0.4$")
    bx.set_title(r"(b) local exponent per interval of $k$", loc="left")
    bx.legend(loc="best")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
