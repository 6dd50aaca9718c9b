#!/usr/bin/python3
"""How a collision count grows as k -> infinity, from the JSON that `granchain reproduce --figure
limit-free` or `limit-driven` writes.

Usage: /usr/bin/python3 plots/limit_exponents.py DATA.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) the local exponent d ln n / d ln k per decade against k, one curve per series, with errors;
(b) the local exponent times ln k at the middle of its interval: the beta of (ln k)^beta, flat for
    a power of ln k, rising toward J for a polynomial of degree J in ln k, and rising by alpha ln 10
    per decade for c k^alpha (ln k)^beta;
(c)-(g) the pulls (n - model) / sigma of the five candidate forms, one panel per form, over the
    fitted range. Error bars are one standard error.
"""
import sys

import numpy as np

from plot_common import load, plt, save, usage

FORMS = ["power law", "a + b ln k", "a + b ln k + c (ln k)^2", "power law with log", "power of ln k"]
TEX = {"power law": r"$c\,k^\alpha$", "a + b ln k": r"$a + b \ln k$",
       "a + b ln k + c (ln k)^2": r"$a + b\ln k + c(\ln k)^2$",
       "power law with log": r"$c\,k^\alpha (\ln k)^\beta$", "power of ln k": r"$c\,(\ln k)^\beta$"}


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig = plt.figure(figsize=(16, 8))
    grid = fig.add_gridspec(2, 10, height_ratios=[1.3, 1])
    ax_a = fig.add_subplot(grid[0, 0:5])
    ax_b = fig.add_subplot(grid[0, 5:10])
    pulls = [fig.add_subplot(grid[1, 2 * i:2 * i + 2]) for i in range(len(FORMS))]
    y_label = data.get("y_label", "n")
    ylab = r"$n_{\rm tot}$" if y_label == "n_tot" else r"$n_{\rm coll}$"
    for s in data["series"]:
        local = s.get("local", [])
        if local:
            mid = np.array([0.5 * (np.log10(l["k1"]) + np.log10(l["k2"])) for l in local])
            a = np.array([l["alpha"] for l in local], dtype=float)
            e = np.array([l["error"] for l in local], dtype=float)
            line = ax_a.errorbar(mid, a, yerr=e, fmt="o-", ms=3, lw=0.8, capsize=2, label=s["label"])
            color = line[0].get_color()
        else:
            color = None
        if local:
            ln_mid = mid * np.log(10.0)
            ax_b.errorbar(mid, a * ln_mid, yerr=e * ln_mid, fmt="o-", ms=3, lw=0.8, capsize=2, color=color, label=s["label"])
        fit = s.get("fit")
        if fit:
            kf = np.log10(np.array(fit["k"], dtype=float))
            for f in fit["forms"]:
                if f["name"] in FORMS:
                    pulls[FORMS.index(f["name"])].plot(kf, f["pulls"], "o-", ms=3, lw=0.7, color=color)
    ax_a.set_xlabel(r"$\log_{10} k$")
    ax_a.set_ylabel(r"local exponent $d\ln %s / d\ln k$" % ylab.strip("$"))
    ax_a.set_title("(a) %s: local exponent per decade" % data.get("title", ""), fontsize=10)
    ax_a.legend(fontsize=8, ncol=2)
    ax_b.set_xlabel(r"$\log_{10} k$")
    ax_b.set_ylabel(r"local exponent $\times \ln k$")
    ax_b.set_title(r"(b) the $\beta$ of $(\ln k)^\beta$: flat for a power of $\ln k$", fontsize=10)
    ax_b.legend(fontsize=7, ncol=2)
    for i, ax in enumerate(pulls):
        ax.axhline(0, color="k", lw=0.5)
        ax.axhspan(-2, 2, color="0.9")
        ax.set_xlabel(r"$\log_{10} k$")
        ax.set_title("(%s) pulls: %s" % ("cdefg"[i], TEX[FORMS[i]]), fontsize=9)
    pulls[0].set_ylabel(r"$(n - {\rm model})/\sigma$")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
