#!/usr/bin/python3
"""The paper's Fig. 1dmodel, drawn with a simulated column (`granchain reproduce --figure fig1`).

Usage: /usr/bin/python3 plots/model_sketch.py trace.csv PREFIX   -> PREFIX.png and PREFIX.pdf
trace.csv: columns t, z1, ..., zN (granchain trace). (a) a sketch of granular flow down a slope
and the line z perpendicular to it along which the model lets particles move; (b) the model: the
column at the last sample, spheres of diameter 1 above the thermal floor at z = 0; (c) z_i(t).
"""
import sys

import numpy as np
from matplotlib.patches import Circle, Rectangle

from plot_common import PAGE, figure, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = np.genfromtxt(argv[1], delimiter=",", names=True)
    names = data.dtype.names
    t = data[names[0]]
    z = np.array([data[n] for n in names[1:]])  # z[i][s]
    fig, axes = figure(PAGE, 3.0, ncols=3, gridspec_kw={"width_ratios": [1.3, 0.6, 1.4]})

    # (a) the slope: a bed of grains on an incline, z along the normal.
    ax = axes[0]
    theta = np.radians(25)
    u = np.array([np.cos(theta), -np.sin(theta)])  # down the slope
    n = np.array([np.sin(theta), np.cos(theta)])   # normal to it
    ax.plot([0, 10 * u[0]], [0, 10 * u[1]], "k-", lw=1.5)
    rng = np.random.default_rng(3)
    for j in range(18):
        for layer in range(4):
            c = (0.5 + j * 0.52) * u + (0.27 + layer * 0.5 + 0.04 * rng.standard_normal()) * n
            ax.add_patch(Circle(c, 0.25, fc="0.8" if j != 8 else "tab:orange", ec="k", lw=0.5))
    base = 8.5 * 0.52 * u
    ax.annotate("", xy=base + 3.2 * n, xytext=base, arrowprops={"arrowstyle": "->", "lw": 1.2})
    ax.text(*(base + 3.35 * n), "z", fontsize=8)
    ax.annotate("", xy=(7.2, -0.6), xytext=(5.4, 0.3), arrowprops={"arrowstyle": "->", "color": "tab:blue"})
    ax.text(6.4, 0.3, "flow", color="tab:blue")
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title("(a) slope flow; motion normal to it", loc="left")

    # (b) the model: the simulated column at the last sample.
    ax = axes[1]
    zs = z[:, -1]
    for i, zi in enumerate(zs):
        ax.add_patch(Circle((0, zi), 0.5, fc="tab:orange" if i == 0 else "0.85", ec="k", lw=0.6))
    ax.add_patch(Rectangle((-1.2, -0.6), 2.4, 0.6, hatch="////", fc="white", ec="k", lw=0.8))
    ax.text(-1.2, -0.9, "thermal floor, $T_0$", fontsize=7, va="top")
    ax.text(0.7, zs[0], "$i = 1$", fontsize=7, va="center")
    ax.text(0.7, zs[-1], "$i = N$", fontsize=7, va="center")
    ax.annotate("", xy=(-1.6, zs[-1] - 3), xytext=(-1.6, zs[-1]), arrowprops={"arrowstyle": "->"})
    ax.text(-2.2, zs[-1] - 1.5, "$g$", fontsize=8)
    ax.set_xlim(-2.6, 3.8)
    ax.set_ylim(-2.6, zs[-1] + 1.5)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title("(b) the model, $t = %g$" % t[-1], loc="left")

    # (c) the same column's z_i(t).
    ax = axes[2]
    for i in range(z.shape[0]):
        ax.plot(t, z[i], lw=0.6, color="tab:orange" if i == 0 else "k")
    ax.axhline(0, color="k", lw=1.5)
    ax.set_xlabel(r"$t$")
    ax.set_ylabel(r"$z_i$")
    ax.set_xlim(t[0], t[-1])
    ax.set_title(r"(c) $z_i(t)$ of the simulated column", loc="left")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
