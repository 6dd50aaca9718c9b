#!/usr/bin/python3
"""The paper's Fig. bifurcationdiagram from `granchain reproduce --figure fig6` (fig6.json).

Usage: /usr/bin/python3 plots/bifurcation.py fig6.json PREFIX   -> PREFIX.png and PREFIX.pdf
1 - e_c1 from b -> 0 (points with one-standard-error bars) and the classification boundary (the bracket
between the last collapsing and the first uncollapsing e, thin), 1 - e_c2 as the bracket where the
curvature is convex by 2 errors / not (squares) and where it changes sign (diamonds, the paper's
reading), against 1/N; the fits (1 - e_c) = A/N of this data (solid) and the paper's A = 2.6 and 3.0
(dashed, dash-dotted) and its Table 1 values for N = 25, 50 (open symbols); shaded: the e range where
the profiles show the partially condensed state.
"""
import sys

import numpy as np

from plot_common import load, plt, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig, ax = plt.subplots(figsize=(7, 5))
    fams = sorted(data["families"], key=lambda f: f["N"])
    inv = np.array([1.0 / f["N"] for f in fams])
    for f in fams:
        x = 1.0 / f["N"]
        if f["e_c1"]:
            ax.errorbar(x, 1 - f["e_c1"]["value"], yerr=f["e_c1"]["error"], fmt="o", color="tab:blue", capsize=3, ms=4)
        if f.get("boundary"):
            lo, hi = 1 - f["boundary"]["high"], 1 - f["boundary"]["low"]
            ax.errorbar(x * 1.02, 0.5 * (lo + hi), yerr=0.5 * (hi - lo), fmt="_", color="tab:cyan", capsize=4, ms=8)
        if f["e_c2"]:
            lo, hi = 1 - f["e_c2"]["high"], 1 - f["e_c2"]["low"]
            ax.errorbar(x, 0.5 * (lo + hi), yerr=0.5 * (hi - lo), fmt="s", color="tab:red", capsize=3, ms=4)
        if f.get("e_c2_sign"):
            ax.errorbar(x * 0.98, 1 - f["e_c2_sign"]["value"], yerr=f["e_c2_sign"]["error"], fmt="D", color="tab:orange", capsize=3, ms=4)
    # The partially condensed region: between the smallest and largest 1 - e flagged, per N.
    xs, lows, highs = [], [], []
    for f in fams:
        if f["condensed_e"]:
            xs.append(1.0 / f["N"])
            lows.append(1 - max(f["condensed_e"]))
            highs.append(1 - min(f["condensed_e"]))
    if len(xs) >= 2:
        ax.fill_between(xs, lows, highs, color="0.85", label=r"partially condensed ($K_i$ dip, hot layer above)")
    elif xs:
        ax.vlines(xs, lows, highs, color="0.7", lw=6, label=r"partially condensed ($K_i$ dip, hot layer above)")
    # The paper's own values for N = 25 and 50 (its Table 1, k_B T0 = 1), open symbols.
    for N, ec1, lo2, hi2 in ((25, 0.894, 0.878, 0.884), (50, 0.944, 0.936, 0.942)):
        ax.plot(1.0 / N, 1 - ec1, "o", mfc="none", color="tab:blue", ms=7)
        ax.errorbar(1.0 / N, 1 - 0.5 * (lo2 + hi2), yerr=0.5 * (hi2 - lo2), fmt="s", mfc="none", color="tab:red", ms=7, capsize=3)
    ax.plot([], [], "o", mfc="none", color="0.3", label=r"paper, Table 1 ($N$ = 25, 50)")
    xx = np.linspace(0, inv.max() * 1.1 if len(inv) else 0.06, 50)
    ax.plot(xx, 2.6 * xx, "k--", lw=0.8, label=r"paper: $2.6/N$")
    ax.plot(xx, 3.0 * xx, "k-.", lw=0.8, label=r"paper: $3.0/N$")
    if data.get("A1"):
        ax.plot(xx, data["A1"]["A"] * xx, color="tab:blue", lw=0.8, label=r"fit $e_{c1}$: $A$ = %.2f" % data["A1"]["A"])
    if data.get("A1_boundary"):
        ax.plot(xx, data["A1_boundary"]["A"] * xx, color="tab:cyan", lw=0.8, label=r"fit boundary: $A$ = %.2f" % data["A1_boundary"]["A"])
    if data.get("A2"):
        ax.plot(xx, data["A2"]["A"] * xx, color="tab:red", lw=0.8, label=r"fit $e_{c2}$: $A$ = %.2f" % data["A2"]["A"])
    if data.get("A2_sign"):
        ax.plot(xx, data["A2_sign"]["A"] * xx, color="tab:orange", lw=0.8, label=r"fit $e_{c2}$ (sign): $A$ = %.2f" % data["A2_sign"]["A"])
    ax.plot([], [], "o", color="tab:blue", label=r"$1 - e_{c1}$ ($b \to 0$)")
    ax.plot([], [], "_", color="tab:cyan", ms=8, label=r"classification boundary")
    ax.plot([], [], "s", color="tab:red", label=r"$1 - e_{c2}$ (convex by 2 errors / not)")
    ax.plot([], [], "D", color="tab:orange", label=r"$1 - e_{c2}$ (curvature changes sign)")
    ax.set_xlim(0, xx.max())
    # The y range of the points themselves: a wide e_c2 bracket (one power-law e far below the
    # critical region) is clipped rather than squeezing the rest.
    tops = [3.0 * xx.max()]
    for f in fams:
        tops += [1 - f["e_c1"]["value"] + f["e_c1"]["error"]] if f["e_c1"] else []
        tops += [1 - f["boundary"]["low"]] if f.get("boundary") else []
        if f.get("e_c2_sign") and f["e_c2_sign"]["error"] < 0.05:
            tops.append(1 - f["e_c2_sign"]["value"] + f["e_c2_sign"]["error"])
        if f["e_c2"] and f["e_c2"]["high"] - f["e_c2"]["low"] < 0.05:
            tops.append(1 - f["e_c2"]["low"])
    ax.set_ylim(0, 1.15 * max(tops))
    ax.set_xlabel(r"$1/N$")
    ax.set_ylabel(r"$1 - e$")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    ax.set_title("power-law collapse (top), logarithmic, uncollapsing (bottom)", fontsize=10)
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
