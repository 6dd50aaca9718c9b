#!/usr/bin/python3
"""The paper's Fig. threebodycollapse from a simulated three-body collapse (`reproduce --figure fig2`).

Usage: /usr/bin/python3 plots/three_body.py trace.csv events.csv PREFIX q tau_c
(a) z_i(t) of the three particles; (b) the intervals t12 between successive collisions (contact
ends) of the pair (1, 2) against their index n, on a log scale, with the geometric law q^n of
Eq. (deltat12) through the third interval and the contact time tau_c.
"""
import sys

import numpy as np

from plot_common import PAGE, figure, save, usage


def main(argv):
    if usage(__doc__, argv, 5):
        return 2
    data = np.genfromtxt(argv[1], delimiter=",", names=True)
    names = data.dtype.names
    ev = np.genfromtxt(argv[2], delimiter=",", names=True, dtype=None, encoding="utf-8")
    q, tau_c = float(argv[4]), float(argv[5])
    fig, axes = figure(PAGE, 2.6, ncols=2)
    ax = axes[0]
    for i, n in enumerate(names[1:]):
        ax.plot(data[names[0]], data[n], lw=1.0, label="particle %d" % (i + 1))
    ax.set_xlabel(r"$t$")
    ax.set_ylabel(r"$z_i$")
    ax.legend()
    ax.set_title(r"(a) three particles collapse: $e = 0.065 < e_c(3)$", loc="left")
    ends = np.atleast_1d(ev)
    t12 = np.array([row["t"] for row in ends if row["kind"] == "contact_end" and row["i"] == 1 and row["j"] == 2])
    ax = axes[1]
    if len(t12) >= 2:
        dt = np.diff(t12)
        idx = np.arange(1, len(dt) + 1)
        ax.semilogy(idx, dt, "o", label=r"measured $t_{12}$")
        a = min(2, len(dt) - 1)  # anchored at the third interval: the first two still carry the launch
        ax.semilogy(idx, dt[a] * q ** (idx - 1 - a), "--", label=r"$q^n$, $q$ = %.4f (Eq. def_q)" % q)
        ax.axhline(tau_c, color="0.5", lw=0.8, ls=":", label=r"$\tau_c$")
    ax.set_xlabel(r"$n$ (collisions of the pair 1–2)")
    ax.set_ylabel(r"interval $t_{12}$")
    ax.legend()
    ax.set_title("(b) geometric intervals", loc="left")
    save(fig, argv[3])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
