#!/usr/bin/python3
"""Collision sequences of free-space collapses, from the JSON that `granchain reproduce --figure
intervals` writes.

Usage: /usr/bin/python3 plots/intervals.py intervals.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) hard spheres: remaining time tau_n = t* - t_n to the collapse against the collision number n
    for a few launches (log tau against n: a geometric sequence is a straight line);
(b) the same against log n (a power of n is a straight line);
(c) collisions n(tau) before the hard sequence comes within tau of the collapse, against the k
    whose tau_c is tau, beside the soft spheres' n_tot(k);
(d) gaps between successive collisions in units of tau_c, soft spheres, one curve per k (a scaling
    plot: curves that coincide mean the sequences end at the cut-off the same way at every k), and
    the gaps between successive collisions of one pair at the largest k (dashed); overlapping
    contacts (negative gaps) are counted in the total but not drawn;
(e) collapse events per launch and collisions per event against k; cascades (events less than
    1000 tau_c apart) per launch and events per cascade;
(f) particles per collapse event (soft, largest k) and in the final hard-sphere collapse.
"""
import sys

import numpy as np

from plot_common import load, plt, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig, axes = plt.subplots(2, 3, figsize=(15, 8.5))
    ax = axes.ravel()
    styles = ["-", "--"]
    for j, h in enumerate(data["hard"]):
        for i, s in enumerate(h["samples"][:3]):
            n = np.array(s["n"], dtype=float)
            tau = np.array(s["tau"], dtype=float)
            label = r"$e = %g$" % h["e"] if i == 0 else None
            ax[0].semilogy(n, tau, styles[j % 2], lw=0.8, color="C%d" % j, label=label)
            ax[1].loglog(n, tau, styles[j % 2], lw=0.8, color="C%d" % j, label=label)
        k = np.array(h["k_equiv"], dtype=float)
        nn = np.array(h["n"], dtype=float)
        ne = np.array(h["n_error"], dtype=float)
        ax[2].errorbar(k, nn, yerr=ne, fmt="s--", ms=3, lw=0.8, color="C%d" % j,
                       label=r"hard $n(\tau)$, $e = %g$" % h["e"])
        if h["particles"]:
            p = np.array(h["particles"], dtype=float)
            ax[5].hist(p, bins=np.arange(0.5, data["N"] + 1.5), histtype="step", density=True, color="C%d" % j, lw=1.5,
                       label=r"hard, final collapse, $e = %g$" % h["e"])
    for j, s in enumerate(data["soft"]):
        per_k = s["per_k"]
        k = np.array([p["k"] for p in per_k])
        n = np.array([p["n_tot"] for p in per_k])
        ne = np.array([p["n_tot_error"] for p in per_k])
        ax[2].errorbar(k, n, yerr=ne, fmt="o-", ms=4, lw=1, color="C%d" % j, label=r"soft $n_{\rm tot}(k)$, $e = %g$" % s["e"])
        ev = np.array([p["events"] for p in per_k])
        eve = np.array([p["events_error"] for p in per_k])
        per = np.array([p["per_event"] for p in per_k])
        pere = np.array([p["per_event_error"] for p in per_k])
        ax[4].errorbar(k, ev, yerr=eve, fmt="o-", ms=4, color="C%d" % j, label=r"events per launch, $e = %g$" % s["e"])
        ax[4].errorbar(k, per, yerr=pere, fmt="s--", ms=4, color="C%d" % j, label=r"collisions per event, $e = %g$" % s["e"])
        if "cascades" in per_k[0]:
            ca = np.array([p["cascades"] for p in per_k])
            cae = np.array([p["cascades_error"] for p in per_k])
            epc = np.array([p["events_per_cascade"] for p in per_k])
            ax[4].errorbar(k, ca, yerr=cae, fmt="^:", ms=4, color="C%d" % j, label=r"cascades per launch, $e = %g$" % s["e"])
            ax[4].plot(k, epc, "v-.", ms=4, lw=0.8, color="C%d" % j, label=r"events per cascade, $e = %g$" % s["e"])
        edges = np.array(s["edges"], dtype=float)
        centres = np.sqrt(edges[1:] * edges[:-1])
        if j == 0:
            for i, p in enumerate(per_k):
                h = np.array(p["gap_hist"], dtype=float)[1:-1]
                ax[3].loglog(centres, h / np.log10(edges[1:] / edges[:-1]), "o-", ms=3, lw=0.8, color=plt.cm.viridis(i / max(1, len(per_k) - 1)),
                             label=r"$k = 10^{%d}$" % round(np.log10(p["k"])))
            pair = np.array(per_k[-1]["pair_gap_hist"], dtype=float)
            if pair.sum() > 0:
                ax[3].loglog(centres, pair[1:-1] / pair.sum() / np.log10(edges[1:] / edges[:-1]), "k--", lw=0.8,
                             label=r"same pair, $k = 10^{%d}$" % round(np.log10(per_k[-1]["k"])))
            ax[3].set_title(r"(d) soft, $e = %g$: gaps between collisions" % s["e"], fontsize=10)
        last = per_k[-1]
        ph = np.array(last["particles_hist"], dtype=float)
        if ph.sum() > 0:
            ax[5].step(np.arange(len(ph)), ph / ph.sum(), where="mid", color="C%d" % j, lw=0.8, ls=":",
                       label=r"soft events, $k = 10^{%d}$, $e = %g$" % (round(np.log10(last["k"])), s["e"]))
    ax[0].set_xlabel(r"collision number $n$")
    ax[0].set_ylabel(r"$\tau_n = t^* - t_n$")
    ax[0].set_title("(a) hard spheres: geometric is a straight line", fontsize=10)
    ax[1].set_xlabel(r"collision number $n$")
    ax[1].set_ylabel(r"$\tau_n$")
    ax[1].set_title(r"(b) a power of $n$ is a straight line", fontsize=10)
    ax[2].set_xscale("log")
    ax[2].set_yscale("log")
    ax[2].set_xlabel(r"$k$ (hard: the $k$ with $\tau_c(k) = \tau$)")
    ax[2].set_ylabel("collisions")
    ax[2].set_title("(c) first collapse (hard) against all collisions (soft)", fontsize=10)
    ax[3].set_xlabel(r"gap $/\,\tau_c$")
    ax[3].set_ylabel("fraction per decade")
    ax[3].axvline(data["event_gap"], color="k", lw=0.5, ls="--")
    ax[4].set_xscale("log")
    ax[4].set_yscale("log")
    ax[4].set_xlabel(r"$k$")
    ax[4].set_ylabel("count")
    ax[4].set_title("(e) soft: collapse events and cascades", fontsize=10)
    ax[5].set_xlabel("particles")
    ax[5].set_ylabel("fraction")
    ax[5].set_title("(f) particles in a collapse", fontsize=10)
    for a in ax:
        a.legend(fontsize=7)
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
