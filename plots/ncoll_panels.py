#!/usr/bin/python3
"""n_coll(k, e) panels in the manner of the paper's Fig. cfreqlogN25, from `granchain analyze --json`.

Usage: /usr/bin/python3 plots/ncoll_panels.py analysis.json PREFIX
For every (engine, N, T0) of the analysis writes PREFIX_N<N>_T0<T0>_<engine>.png and .pdf with
(a) n_coll against log10 k for the critical region 1 - 5/N <= e <= 1 - 2.5/N (the paper's
    0.80 ... 0.90 at N = 25), with the fitted a + b log10 k where logarithmic; for N < 10 (Fig.
    cflogk) every e,
(b) the same for 1 - 3.25/N <= e <= 1 - 2.5/N (0.87 ... 0.90 at N = 25); for N < 10 the e around
    the free-space critical values e_c(3) ... e_c(N + 1) given as ec_lines,
(c) log10 n_coll against log10 k for e = 0.1, 0.2, ..., 1.0, with the fitted c k^alpha where
    power-law,
(d) n_coll against e for every k, with e_c1 (and its error), the classification boundary and the
    e_c2 bracket, and the paper's e_c1 and e_c2 where the analysis carries them ("paper"); for
    N >= 10 an inset enlarges the critical region,
(e) the local exponent per decade of k of the curves at e = 0.1 ... 0.4 (Table 1's), with their
    global alpha as dashed lines: the drift the global fit averages.
A panel whose e range holds no curve shows every curve instead. Colours encode e (colour bars) in
(a)-(c), (e) and k in (d). Error bars are one standard error. Prints the files written.
"""
import sys

import numpy as np

from plot_common import load, plt, save, usage


def arrays(c):
    k = np.array([p["k"] for p in c["n_coll_of_k"]])
    n = np.array([p["n_coll"] for p in c["n_coll_of_k"]])
    s = np.array([p["error"] for p in c["n_coll_of_k"]])
    return k, n, s


def in_range(curves, lo, hi):
    chosen = [c for c in curves if lo - 1e-9 <= c["e"] <= hi + 1e-9]
    return chosen if chosen else curves


def against_log_k(ax, curves, k_min, log_n, title, fig):
    es = [c["e"] for c in curves]
    lo, hi = min(es), max(es)
    cmap = plt.get_cmap("viridis")
    norm = plt.Normalize(lo, hi if hi > lo else lo + 1e-9)
    for c in curves:
        colour = cmap(norm(c["e"]))
        k, n, s = arrays(c)
        x = np.log10(k)
        y, dy = (np.log10(n), s / (n * np.log(10))) if log_n else (n, s)
        marker = "o" if not c.get("non_stationary_k") else "x"
        ax.errorbar(x, y, yerr=dy, fmt=marker, ms=3, color=colour, capsize=2)
        if c.get("classified"):
            xa = x[k >= k_min] if np.any(k >= k_min) else x
            xx = np.linspace(xa.min(), xa.max(), 50)  # the fit's own range
            if not log_n and c["regime"] == "logarithmic":
                ax.plot(xx, c["log_fit"]["a"] + c["log_fit"]["b"] * xx, "-", color=colour, lw=0.8)
            if log_n and c["regime"] == "power-law":
                pf = c["power_fit"]
                ax.plot(xx, np.log10(pf["c"]) + pf["alpha"] * xx, "-", color=colour, lw=0.8)
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=ax, label="$e$", fraction=0.05, pad=0.02)
    ax.set_xlabel(r"$\log_{10} k$")
    ax.set_ylabel(r"$\log_{10} n_{\rm coll}$" if log_n else r"$n_{\rm coll}$")
    ax.set_title(title, fontsize=10)


def against_e(ax, family, curves, inset_range):
    ks = sorted({p["k"] for c in curves for p in c["n_coll_of_k"]})
    kmap = plt.get_cmap("plasma")
    targets = [ax]
    inset = None
    if inset_range:
        inset = ax.inset_axes([0.07, 0.56, 0.42, 0.3])  # between the curves of the two largest k
        targets.append(inset)
    for i, k in enumerate(ks):
        pts = sorted((c["e"], p["n_coll"], p["error"]) for c in curves for p in c["n_coll_of_k"] if p["k"] == k)
        e, n, s = (np.array(v) for v in zip(*pts))
        colour = kmap(i / max(1, len(ks) - 1))
        ax.errorbar(e, n, yerr=s, fmt="o-", ms=2.5, lw=0.8, color=colour, label=r"$k = 10^{%d}$" % round(np.log10(k)),
                    capsize=1.5)
        if inset is not None:
            sel = (e >= inset_range[0]) & (e <= inset_range[1])
            inset.errorbar(e[sel], n[sel], yerr=s[sel], fmt="o-", ms=2, lw=0.7, color=colour, capsize=1)
    for i, ec in enumerate(family.get("ec_lines", [])):  # Fig. cfe: e_c(3) ... e_c(N+1)
        ax.axvline(ec, ls=":", color="0.4", lw=0.8, label=r"$e_c(3), \ldots, e_c(N+1)$" if i == 0 else None)
    est = family.get("e_c1_estimate") or {}
    for t in targets:
        first = t is ax
        if family.get("e_c1"):
            v, err = family["e_c1"]["value"], family["e_c1"]["error"]
            t.axvline(v, ls="--", color="k", lw=0.8, label=r"$e_{c1}$ ($b \to 0$)" if first else None)
            t.axvspan(v - err, v + err, color="0.6", alpha=0.25, lw=0)
        if est.get("boundary"):
            b = est["boundary"]
            t.axvspan(b["last_collapsing_e"], b["first_uncollapsing_e"], color="tab:green", alpha=0.35, lw=0,
                      label="classification boundary" if first else None)
        if family.get("e_c2"):
            t.axvspan(family["e_c2"]["low"], family["e_c2"]["high"], color="0.85",
                      label=r"$e_{c2}$ bracket" if first else None)
        paper = family.get("paper") or {}
        if "e_c1" in paper:
            t.axvline(paper["e_c1"], ls="-.", color="tab:red", lw=1.0, label=r"paper: $e_{c1}$" if first else None)
        if "e_c2_low" in paper:
            t.axvspan(paper["e_c2_low"], paper["e_c2_high"], fill=False, hatch="///", edgecolor="tab:red", lw=0,
                      label=r"paper: $e_{c2}$" if first else None)
    if inset is not None:
        inset.set_xlim(*inset_range)
        inset.tick_params(labelsize=8)
    ax.set_xlabel("$e$")
    ax.set_ylabel(r"$n_{\rm coll}$")
    ax.set_title(r"(d) $n_{\rm coll}$ against $e$", fontsize=10)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)


def local_exponents(ax, curves, fig):
    """(e): local exponent per decade of k against the decade's middle, for e = 0.1 ... 0.4."""
    chosen = [c for c in curves if c.get("local_exponents") and any(abs(c["e"] - x) < 1e-9 for x in (0.1, 0.2, 0.3, 0.4))]
    if not chosen:
        ax.set_axis_off()
        return
    cmap = plt.get_cmap("viridis")
    norm = plt.Normalize(0.1, 0.4)
    for c in chosen:
        colour = cmap(norm(c["e"]))
        le = c["local_exponents"]
        x = np.array([0.5 * (np.log10(p["k1"]) + np.log10(p["k2"])) for p in le])
        y = np.array([p["alpha"] for p in le])
        dy = np.array([p["error"] for p in le])
        ax.errorbar(x, y, yerr=dy, fmt="o-", ms=3, lw=0.8, color=colour, capsize=2)
        if c.get("regime") == "power-law":
            ax.axhline(c["power_fit"]["alpha"], ls="--", lw=0.7, color=colour)
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=ax, label="$e$", fraction=0.05, pad=0.02)
    ax.set_xlabel(r"$\log_{10} k$ (middle of each decade)")
    ax.set_ylabel(r"local exponent $\Delta \ln n_{\rm coll} / \Delta \ln k$")
    ax.set_title(r"(e) local $\alpha$ per decade of $k$ (dashed: global $\alpha$)", fontsize=10)


def draw(family, prefix, k_min):
    curves = [c for c in family["curves"] if c["n_coll_of_k"]]
    if not curves:
        return None
    N = family["N"]
    fig = plt.figure(figsize=(17, 10))
    grid = fig.add_gridspec(2, 3)
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1]), fig.add_subplot(grid[0, 2]),
            fig.add_subplot(grid[1, 0:2]), fig.add_subplot(grid[1, 2])]
    if N >= 10:
        wide = in_range(curves, 1 - 5.0 / N, 1 - 2.5 / N)
        narrow = in_range(curves, 1 - 3.25 / N, 1 - 2.5 / N)
    else:  # small N (Figs. cflogk, cfe): every e, then the region of the free-space e_c(n)
        wide = curves
        lines = family.get("ec_lines") or []
        narrow = in_range(curves, min(lines) - 0.02, max(lines) + 0.02) if lines else curves
    tenths = [c for c in curves if abs(10 * c["e"] - round(10 * c["e"])) < 1e-9] or curves
    against_log_k(axes[0], wide, k_min, False, "(a) $e$ = %.3g … %.3g" % (min(c["e"] for c in wide), max(c["e"] for c in wide)), fig)
    against_log_k(axes[1], narrow, k_min, False,
                  "(b) $e$ = %.3g … %.3g" % (min(c["e"] for c in narrow), max(c["e"] for c in narrow)), fig)
    against_log_k(axes[2], tenths, k_min, True, r"(c) $\log n_{\rm coll}$ against $\log k$, $e$ = 0.1, 0.2, …", fig)
    crit = [family["e_c1"]["value"]] if family.get("e_c1") else []
    es = sorted(c["e"] for c in curves)
    inset = None
    if N >= 10 and (family.get("e_c2") or crit):  # the paper's Fig. cfe (small N) has no inset
        lo = min([family["e_c2"]["low"]] if family.get("e_c2") else crit) - 0.03
        hi = max(crit + ([family["e_c2"]["high"]] if family.get("e_c2") else [])) + 0.03
        if sum(1 for e in es if lo <= e <= hi) >= 3:
            inset = (lo, hi)
    against_e(axes[3], family, curves, inset)
    local_exponents(axes[4], curves, fig)
    fig.suptitle(r"$N = %d$, $k_B T_0 = %g$, engine %s (crosses: window not stationary)" % (N, family["T0"], family["engine"]),
                 fontsize=12)
    stem = family.get("stem") or "%s_N%d_T0%g_%s" % (prefix, N, family["T0"], family["engine"])
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
