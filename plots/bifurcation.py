#!/usr/bin/python3
"""The paper's Fig. bifurcationdiagram from `granchain reproduce --figure fig6` (fig6.json).

Usage: /usr/bin/python3 plots/bifurcation.py fig6.json PREFIX   -> PREFIX.png and PREFIX.pdf
Against 1/N (top axis: N): 1 - e_c1 from b -> 0 (circles with one-standard-error bars) and
1 - e_c2 where the curvature changes sign (diamonds, the paper's reading, one standard error);
two brackets "[" (intervals, not errors): the classification boundary (between the last
collapsing and the first uncollapsing e) and e_c2 from the curvature (between the last e convex
by 2 errors and the first that is not); an end beyond the axes is an arrow head. Lines: the fits
(1 - e_c) = A/N of this data (solid, the colour of their points) and the paper's A = 2.6 and 3.0
(black dashed, dash-dotted); open symbols: the paper's Table 1 for N = 25, 50; shaded: the e range
where the profiles show the partially condensed state.
"""
import sys

import numpy as np

from plot_common import PAGE, bracket, bracket_handle, figure, legend_axes, load, plt, save, usage

E_C1, BOUNDARY, E_C2, E_C2_SIGN = "#1f4e9c", "#2a9d8f", "#c0392b", "#e07b00"


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig, (ax, lax) = figure(PAGE, 3.2, ncols=2, gridspec_kw={"width_ratios": [1.35, 1]})
    fams = sorted(data["families"], key=lambda f: f["N"])
    inv = np.array([1.0 / f["N"] for f in fams])
    xx = np.linspace(0, inv.max() * 1.1 if len(inv) else 0.06, 50)
    handles, labels = [], []

    def entry(handle, label):
        handles.append(handle)
        labels.append(label)

    # The y range of the points themselves: a bracket wider than 0.05 in e (a power-law e far below
    # the critical region) ends in an arrow rather than squeezing the rest.
    tops = [3.0 * xx.max()]
    for f in fams:
        tops += [1 - f["e_c1"]["value"] + f["e_c1"]["error"]] if f["e_c1"] else []
        tops += [1 - f["boundary"]["low"]] if f.get("boundary") else []
        if f.get("e_c2_sign") and f["e_c2_sign"]["error"] < 0.05:
            tops.append(1 - f["e_c2_sign"]["value"] + f["e_c2_sign"]["error"])
        if f["e_c2"] and f["e_c2"]["high"] - f["e_c2"]["low"] < 0.05:
            tops.append(1 - f["e_c2"]["low"])
    ax.set_xlim(0, xx.max())
    ax.set_ylim(0, 1.12 * max(tops))

    # The partially condensed region: between the smallest and largest 1 - e flagged, per N.
    xs, lows, highs = [], [], []
    for f in fams:
        if f["condensed_e"]:
            xs.append(1.0 / f["N"])
            lows.append(1 - max(f["condensed_e"]))
            highs.append(1 - min(f["condensed_e"]))
    if xs:
        if len(xs) >= 2:
            ax.fill_between(xs, lows, highs, color="0.88", lw=0)
        else:
            ax.vlines(xs, lows, highs, color="0.8", lw=6)
        entry(plt.Rectangle((0, 0), 1, 1, color="0.88"), r"partially condensed ($K_i$ dip, hot layer above)")

    # Measured points: error bars for e_c1 and e_c2 (sign), brackets for the two intervals, each
    # kind a few points apart sideways so that none hides another.
    for f in fams:
        x = 1.0 / f["N"]
        if f["e_c1"]:
            ax.errorbar(x, 1 - f["e_c1"]["value"], yerr=f["e_c1"]["error"], fmt="o", color=E_C1, ms=3.5, capsize=2)
        if f.get("e_c2_sign"):
            ax.errorbar(x, 1 - f["e_c2_sign"]["value"], yerr=f["e_c2_sign"]["error"], fmt="D", color=E_C2_SIGN, ms=3,
                        capsize=2, transform=ax.transData + _shift(fig, -3))
        if f.get("boundary"):
            bracket(ax, x, 1 - f["boundary"]["high"], 1 - f["boundary"]["low"], BOUNDARY, offset_pt=3)
        if f["e_c2"]:
            bracket(ax, x, 1 - f["e_c2"]["high"], 1 - f["e_c2"]["low"], E_C2, offset_pt=6)

    # The paper's Table 1 (N = 25, 50, k_B T0 = 1): open symbols.
    for N, ec1, lo2, hi2 in ((25, 0.894, 0.878, 0.884), (50, 0.944, 0.936, 0.942)):
        ax.plot(1.0 / N, 1 - ec1, "o", mfc="none", color=E_C1, ms=6, mew=0.8)
        ax.plot(1.0 / N, 1 - 0.5 * (lo2 + hi2), "s", mfc="none", color=E_C2, ms=6, mew=0.8)
    entry(plt.Line2D([], [], ls="none", marker="o", mfc="none", color="0.3", ms=6, mew=0.8),
          r"paper, Table 1 ($N$ = 25, 50): $e_{c1}$ (circle), $e_{c2}$ (square)")

    ax.plot(xx, 2.6 * xx, "k--", lw=0.7)
    ax.plot(xx, 3.0 * xx, "k-.", lw=0.7)
    entry(plt.Line2D([], [], color="k", ls="--", lw=0.7), r"paper: $2.6/N$")
    entry(plt.Line2D([], [], color="k", ls="-.", lw=0.7), r"paper: $3.0/N$")
    kinds = (("A1", E_C1, "o", r"$1 - e_{c1}$ ($b \to 0$), error bar"),
             ("A1_boundary", BOUNDARY, None, r"classification boundary, bracket"),
             ("A2", E_C2, None, r"$1 - e_{c2}$, convex by 2 errors / not, bracket"),
             ("A2_sign", E_C2_SIGN, "D", r"$1 - e_{c2}$, curvature changes sign, error bar"))
    for key, colour, marker, label in kinds:
        point = (plt.Line2D([], [], ls="none", marker=marker, color=colour, ms=3.5) if marker
                 else bracket_handle(colour))
        if data.get(key):
            A = data[key]["A"]
            ax.plot(xx, A * xx, color=colour, lw=0.8)
            entry((point, plt.Line2D([], [], color=colour, lw=0.8)), label + "; fit $A$ = %.2f" % A)
        else:
            entry(point, label)

    # The same 1/N on top, a tick at each N drawn; a label only where it clears the last one (from
    # the largest N), so that the crowded large N near 1/N = 0 do not print over each other.
    top = ax.secondary_xaxis("top")
    ns = sorted({f["N"] for f in fams}, reverse=True)
    gap = 0.035 * (ax.get_xlim()[1] - ax.get_xlim()[0])
    top_labels, last = [], None
    for n in ns:
        keep = last is None or 1.0 / n - last >= gap
        top_labels.append("%d" % n if keep else "")
        last = 1.0 / n if keep else last
    top.set_xticks([1.0 / n for n in ns])
    top.set_xticklabels(top_labels, fontsize=6)
    top.set_xlabel(r"$N$")
    ax.set_xlabel(r"$1/N$")
    ax.set_ylabel(r"$1 - e$")
    ax.text(0.97, 0.03, "above the lines: power-law collapse;\nbelow: logarithmic, then uncollapsing",
            transform=ax.transAxes, ha="right", va="bottom", fontsize=7)
    legend_axes(lax, handles, labels, loc="center left", handlelength=2.4)
    save(fig, argv[2])
    return 0


def _shift(fig, points):
    from matplotlib.transforms import ScaledTranslation
    return ScaledTranslation(points / 72.0, 0, fig.dpi_scale_trans)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
