#!/usr/bin/python3
"""Space-time diagram z_i(t) from `granchain trace` CSV output (columns t, z1, ..., zN).

Usage: /usr/bin/python3 plots/spacetime.py trace.csv out.png [title]
Writes out.png and the same figure as PDF beside it.
"""
import sys

import numpy as np

from plot_common import COLUMN, figure, save_file


def main(argv):
    if len(argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    data = np.genfromtxt(argv[1], delimiter=",", names=True)
    names = data.dtype.names
    t = data[names[0]]
    fig, ax = figure(COLUMN, 2.6)
    for name in names[1:]:
        ax.plot(t, data[name], lw=0.5, color="k")
    ax.set_xlabel(r"$t$")
    ax.set_ylabel(r"$z_i$ (height of particle $i$)")
    ax.set_xlim(t[0], t[-1])
    if len(argv) > 3:
        ax.set_title(argv[3], loc="left")
    save_file(fig, argv[2])
    stem = argv[2].rsplit(".", 1)[0]
    save_file(fig, stem + ".pdf")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
