#!/usr/bin/python3
"""n_coll(k, e) panels in the manner of the paper's Fig. cfreqlogN25, from `granchain analyze --json`.

Usage: /usr/bin/python3 plots/ncoll_panels.py analysis.json PREFIX
For every (engine, N, T0) of the analysis writes PREFIX_N<N>_T0<T0>_<engine>.png and .pdf with
(a) n_coll against log10 k for every e, with the fitted a + b log10 k where logarithmic,
(b) log10 n_coll against log10 k, with the fitted c k^alpha where power-law,
(c) n_coll against e for every k, with e_c1 and the e_c2 bracket marked.
Error bars are one standard error. Prints the files written.
"""
import sys

import numpy as np

from plot_common import load, plt, save, usage


def draw(family, prefix, k_min):
    curves = [c for c in family["curves"] if c["n_coll_of_k"]]
    if not curves:
        return None
    cmap = plt.get_cmap("viridis")
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    es = [c["e"] for c in curves]
    lo, hi = min(es), max(es)
    for c in curves:
        colour = cmap(0.0 if hi == lo else (c["e"] - lo) / (hi - lo))
        k = np.array([p["k"] for p in c["n_coll_of_k"]])
        n = np.array([p["n_coll"] for p in c["n_coll_of_k"]])
        s = np.array([p["error"] for p in c["n_coll_of_k"]])
        x = np.log10(k)
        label = "e = %g%s" % (c["e"], " (%s)" % c["regime"] if c.get("classified") else "")
        axes[0].errorbar(x, n, yerr=s, fmt="o", ms=3, color=colour, label=label, capsize=2)
        axes[1].errorbar(x, np.log10(n), yerr=s / (n * np.log(10)), fmt="o", ms=3, color=colour, capsize=2)
        if c.get("classified"):
            xa = x[k >= k_min] if np.any(k >= k_min) else x
            xx = np.linspace(xa.min(), xa.max(), 50)  # the fit's own range
            if c["regime"] == "logarithmic":
                axes[0].plot(xx, c["log_fit"]["a"] + c["log_fit"]["b"] * xx, "-", color=colour, lw=0.8)
            if c["regime"] == "power-law":
                pf = c["power_fit"]
                axes[1].plot(xx, np.log10(pf["c"]) + pf["alpha"] * xx, "-", color=colour, lw=0.8)
    ks = sorted({p["k"] for c in curves for p in c["n_coll_of_k"]})
    kmap = plt.get_cmap("plasma")
    for i, k in enumerate(ks):
        pts = [(c["e"], p["n_coll"], p["error"]) for c in curves for p in c["n_coll_of_k"] if p["k"] == k]
        pts.sort()
        e, n, s = (np.array(v) for v in zip(*pts))
        axes[2].errorbar(e, n, yerr=s, fmt="o-", ms=3, lw=0.8, color=kmap(i / max(1, len(ks) - 1)),
                         label="k = %.0e" % k, capsize=2)
    for i, ec in enumerate(family.get("ec_lines", [])):  # Fig. cfe: e_c(3) ... e_c(N+1)
        axes[2].axvline(ec, ls=":", color="0.4", lw=0.8, label="e_c(3..N+1)" if i == 0 else None)
    if family.get("e_c1"):
        axes[2].axvline(family["e_c1"]["value"], ls="--", color="k", lw=0.8, label="e_c1")
    if family.get("e_c2"):
        axes[2].axvspan(family["e_c2"]["low"], family["e_c2"]["high"], color="0.85", label="e_c2 bracket")
    axes[0].set_xlabel("log10 k")
    axes[0].set_ylabel("n_coll")
    axes[0].set_title("(a) n_coll against log k", fontsize=9)
    axes[1].set_xlabel("log10 k")
    axes[1].set_ylabel("log10 n_coll")
    axes[1].set_title("(b) log n_coll against log k", fontsize=9)
    axes[2].set_xlabel("e")
    axes[2].set_ylabel("n_coll")
    axes[2].set_title("(c) n_coll against e", fontsize=9)
    axes[0].legend(fontsize=6, ncol=2)
    axes[2].legend(fontsize=6)
    fig.suptitle("N = %d, k_B T0 = %g, engine %s" % (family["N"], family["T0"], family["engine"]), fontsize=10)
    stem = "%s_N%d_T0%g_%s" % (prefix, family["N"], family["T0"], family["engine"])
    save(fig, stem)
    plt.close(fig)
    return stem + ".png"


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    analysis = load(argv[1])
    for family in analysis["families"]:
        out = draw(family, argv[2], analysis.get("k_min", 0.0))
        if out:
            print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
