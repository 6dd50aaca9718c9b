#!/usr/bin/python3
"""The paper's Fig. partial_cond from `granchain reproduce --figure fig8` (fig8.json).

Usage: /usr/bin/python3 plots/partial_cond.py fig8.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) sigma_i / sigma_0,i (sigma_0,i of the exact elastic column) and (b) K_i against the particle
index i, one curve per e; error bars one standard error; dashed: K_i = k_B T0 / 2 of the elastic
column; log scales. Partially condensed columns (a K_i dip with an interior hot layer above it) are drawn
solid, columns condensed as a whole (a dip, only the surface warmer) dashed, the others dotted.
"""
import sys

import numpy as np

from plot_common import load, plt, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    curves = sorted(data["curves"], key=lambda c: c["e"])
    fig, axes = plt.subplots(2, 1, figsize=(8, 9), sharex=True)
    for j, c in enumerate(curves):
        p = c["profile"]
        i = np.arange(1, len(p["K"]) + 1)
        color = plt.cm.coolwarm(j / max(1, len(curves) - 1))
        state = c.get("state", "partial" if c["condensed"] else "none")
        style = {"partial": "-", "whole": "--"}.get(state, ":")
        label = "$e = %g$%s" % (c["e"], {"partial": " (partially condensed)", "whole": " (condensed)"}.get(state, ""))
        if p["sigma0"]:
            s0 = np.array(p["sigma0"])
            axes[0].errorbar(i, np.array(p["sigma"]) / s0, yerr=np.array(p["sigma_err"]) / s0, fmt="o" + style, ms=2.5,
                             lw=0.9, capsize=1.5, color=color, label=label)
        axes[1].errorbar(i, p["K"], yerr=p["K_err"], fmt="o" + style, ms=2.5, lw=0.9, capsize=1.5, color=color, label=label)
    axes[1].axhline(0.5, color="k", ls="--", lw=0.7, label=r"elastic column: $K_i = k_B T_0 / 2$")
    for ax in axes:
        ax.set_yscale("log")
    axes[0].set_ylabel(r"$\sigma_i / \sigma_{0,i}$")
    axes[1].set_ylabel(r"$K_i$")
    axes[1].set_xlabel(r"particle $i$ (1 = bottom)")
    axes[0].set_title(r"(a) height fluctuation against the elastic column's, $N = %d$, $k = %s$" % (data["N"], data["k"]),
                      fontsize=10)
    axes[1].set_title(r"(b) kinetic energy per particle $K_i$; solid: partially condensed, dashed: condensed as a whole",
                      fontsize=10)
    # One legend for both panels, outside the data.
    handles, labels = axes[1].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=8, loc="center left", bbox_to_anchor=(1.0, 0.5))
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
