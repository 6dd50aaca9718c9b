#!/usr/bin/python3
"""The paper's Fig. partial_cond from `granchain reproduce --figure fig8` (fig8.json).

Usage: /usr/bin/python3 plots/partial_cond.py fig8.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) sigma_i / sigma_0,i (sigma_0,i of the exact elastic column) and (b) K_i against the particle
index i, one curve per e (colour: e, dark blue to green over the critical region, then the
uncondensed e; black: the elastic e = 1); error bars one standard error; dashed grey: K_i = k_B T0 / 2
of the elastic column; log scales. Partially condensed columns (a K_i dip with an interior hot
layer above it) are drawn solid, columns condensed as a whole (a dip, only the surface warmer)
dashed, the others dotted.
"""
import sys

import numpy as np

from plot_common import PAGE, colours, figure, legend_axes, load, plt, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    curves = sorted(data["curves"], key=lambda c: c["e"])
    inelastic = [c for c in curves if c["e"] < 1]
    palette = dict(zip((c["e"] for c in inelastic), colours(len(inelastic))))
    fig, axes = figure(PAGE, 4.6, nrows=2, ncols=2, sharex="col", gridspec_kw={"width_ratios": [1, 0.32]})
    ax_s, ax_k = axes[0][0], axes[1][0]
    for c in curves:
        p = c["profile"]
        i = np.arange(1, len(p["K"]) + 1)
        colour = palette.get(c["e"], "k")
        state = c.get("state", "partial" if c["condensed"] else "none")
        style = {"partial": "-", "whole": "--"}.get(state, ":")
        label = "$e = %g$%s" % (c["e"], {"partial": ", partially condensed", "whole": ", condensed"}.get(state, ""))
        if p["sigma0"]:
            s0 = np.array(p["sigma0"])
            ax_s.errorbar(i, np.array(p["sigma"]) / s0, yerr=np.array(p["sigma_err"]) / s0, fmt="o" + style, ms=2,
                          capsize=1, color=colour, label=label)
        ax_k.errorbar(i, p["K"], yerr=p["K_err"], fmt="o" + style, ms=2, capsize=1, color=colour, label=label)
    ax_k.axhline(0.5, color="0.5", ls="--", lw=0.7, label=r"elastic column: $K_i = k_B T_0 / 2$")
    for ax in (ax_s, ax_k):
        ax.set_yscale("log")
    ax_s.set_ylabel(r"$\sigma_i / \sigma_{0,i}$")
    ax_k.set_ylabel(r"$K_i$")
    ax_k.set_xlabel(r"particle $i$ (1 = bottom)")
    ax_s.set_title(r"(a) height fluctuation against the elastic column's, $N = %d$, $k = %s$" % (data["N"], data["k"]),
                   loc="left")
    ax_k.set_title(r"(b) kinetic energy per particle", loc="left")
    # One legend for both panels, in the right-hand column of the layout (off the data).
    handles, labels = ax_k.get_legend_handles_labels()
    legend_axes(axes[0][1], handles, labels, loc="upper left")
    key = [plt.Line2D([], [], color="0.3", ls=s) for s in ("-", "--", ":")]
    legend_axes(axes[1][1], key, ["partially condensed", "condensed as a whole", "neither"], loc="lower left",
                title="line style", title_fontsize=7)
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
