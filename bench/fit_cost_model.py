#!/usr/bin/python3
"""Calibrates the exact engine's cost model (src/sweep/cost_model.cpp) on timed runs.

The model: ln(seconds per unit of simulated time) = sum_j c_j f_j(N, e, k, T0), with the features
of cost_model.cpp (features() below, in the same order), fitted by weighted least squares. N is held
in the box 3 <= N <= 150 and log10 k in 5 ... 10; beyond N = 150 the feature ln(N / 150) carries the
power of N the cost grows with (fitted here with the rest). x = ln(1 + N (1 - e)) is the column's
own, held at N (1 - e) <= 135; the polynomial in x stops at N (1 - e) = 30, and beyond it (the
power-law side) the rate is a line in x whose slope depends on N: a cubic through the smaller
columns turned over there and made N = 150 at e = 0.1 2.5 times cheaper than e = 0.4, where the
measured cost hardly depends on e.

    /usr/bin/python3 bench/fit_cost_model.py [sample.txt ...] [--short 10 --long 40 --settle 40]
                                             [--runs runs.txt ...] [--seeds odd|even|all]

--runs (repeatable) adds whole runs, one per line: N e k T0 T transient predicted measured seed (as
bench/cost_model_check.sh --list writes them, or a query of a results store, docs/benchmarks.md):
their time (CPU time where stored) over T + transient is the rate, free of the start-up effects that
make a sample's millisecond timings unreliable; --seeds keeps only those with odd or even seeds, so
that the others can check the model. FILE@FACTOR: the list's runs were timed on a machine FACTOR times
slower than the calibration machine (bench/machine_factor.sh measures it); their times are divided
by it, so that every list fits the calibration machine's seconds. The positional sample files (bench/paper_cost.sh --list) give
each point's settled rate, (long - short) / (LONG - SHORT), or the mean over the long run where that
is larger; points whose long run took under 0.05 s weigh 0.05 (mostly the run's fixed overhead).

prints the coefficients as a C++ initialiser and how many points the model predicts within a factor
of 2, for the runs fitted and, with --seeds odd or even, for the others.
"""
import argparse
import math

import numpy as np

from fit_high_k_cost import class_label, class_of  # the tables' classes of N (1 - e)


C_POLY = 30.0  # kXPolynomialMax = ln(1 + C_POLY): the polynomial in x stops at N (1 - e) = 30, a line beyond


def features(N, e, k, T0):
    """The model's features; keep in step with exact_log_rate() in src/sweep/cost_model.cpp."""
    n = min(max(N, 3.0), 150.0)
    lN = math.log(n)
    xc = min(math.log1p(N * (1.0 - e)), math.log1p(135.0))
    x = min(xc, math.log1p(C_POLY))
    h = xc - x  # how far the column lies beyond N (1 - e) = 30, on the power-law side
    lk = min(max(math.log10(k) - 5.0, 0.0), 5.0)
    beyond = math.log(N / 150.0) if N > 150.0 else 0.0
    return [1.0, lN, lN * lN, x, x * x, x ** 3, lk, lk * x, lk * x * x, lk * lN, x * lN, lk * lk, math.log(T0),
            beyond, lk * lk * x, lk * x * lN, h, h * lN]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("lists", nargs="*")
    ap.add_argument("--short", type=float, default=10)
    ap.add_argument("--long", type=float, default=40)
    ap.add_argument("--settle", type=float, default=40)
    ap.add_argument("--runs", action="append", default=[])
    ap.add_argument("--seeds", default="all", choices=["odd", "even", "all"])
    a = ap.parse_args()
    rows, rates, weights = [], [], []
    held_rows, held_rates = [], []  # the runs of the other seeds: the check
    cells = []  # (N, N (1 - e)) of every whole run, fitted ones first, then the held-out ones
    held_cells = []
    for path in a.lists:
        for line in open(path):
            f = line.split()
            N, e, k, T0 = float(f[1]), float(f[2]), float(f[3]), float(f[4])
            ws, wl = float(f[7]), float(f[8])
            rate = max((wl - ws) / (a.long - a.short), wl / (a.settle + a.long))
            rows.append(features(N, e, k, T0))
            rates.append(rate)
            # Runs of a few milliseconds are timed at start-up clock speeds: they weigh little.
            weights.append(1.0 if wl >= 0.05 else 0.05)
    for runs in a.runs:
        path, _, factor = runs.partition("@")
        try:
            factor = float(factor) if factor else 1.0
        except ValueError:
            factor = 0.0
        if not factor > 0.0:
            ap.error("--runs %s: the factor after @ must be a number > 0 (bench/machine_factor.sh prints it)" % runs)
        for line in open(path):
            f = line.split()
            N, e, k, T0, T, tr, wall, seed = (float(f[0]), float(f[1]), float(f[2]), float(f[3]), float(f[4]),
                                              float(f[5]), float(f[7]) / factor, f[8])
            if a.seeds != "all" and (int(seed[-1]) % 2 == 1) != (a.seeds == "odd"):
                held_rows.append(features(N, e, k, T0))
                held_rates.append(wall / (T + tr))
                held_cells.append((N, N * (1.0 - e)))
                continue
            rows.append(features(N, e, k, T0))
            rates.append(wall / (T + tr))
            weights.append(1.0)
            cells.append((N, N * (1.0 - e)))
    X, y, w = np.array(rows), np.log(np.array(rates)), np.array(weights)
    coef, *_ = np.linalg.lstsq(X * w[:, None], y * w, rcond=None)
    ratio = np.exp(X @ coef - y)
    timed = w == 1.0
    within = (ratio > 0.5) & (ratio < 2.0)
    print("// %d points, %d timed above 0.05 s" % (len(y), timed.sum()))
    print("// predicted / measured within a factor of 2: %d of %d (all), %d of %d (timed above 0.05 s);"
          % (within.sum(), len(y), within[timed].sum(), timed.sum()))
    print("// range over those: %.2f .. %.2f" % (ratio[timed].min(), ratio[timed].max()))
    if held_rows:
        held = np.exp(np.array(held_rows) @ coef) / np.array(held_rates)
        print("// held out (the other seeds): %d of %d within a factor of 2, range %.2f .. %.2f"
              % (((held > 0.5) & (held < 2.0)).sum(), len(held), held.min(), held.max()))
    whole = np.log(ratio[len(y) - len(cells):])
    if held_rows:
        whole = np.concatenate([whole, np.log(held)])
    print_cells(cells + held_cells, whole)
    print("constexpr double kExactCoefficients[%d] = {%s};" % (len(coef), ", ".join("%.6g" % c for c in coef)))


def print_cells(cells, log_ratios):
    """measured / predicted of the whole runs (fitted and held out) per N and class of N (1 - e)."""
    groups = {}
    for (N, c), r in zip(cells, log_ratios):
        n_group = (N, "%d" % N) if N >= 100 else ((1, "3 - 6") if N <= 6 else (2, "10 - 50"))
        groups.setdefault((n_group, class_of(c)), []).append(-r)
    print("// whole runs, measured / predicted per N and N (1 - e): runs, geometric mean, within a factor of 2")
    for ((_, n_label), cls), v in sorted(groups.items()):
        v = np.array(v)
        print("//   N %-8s N (1 - e) %-7s %5d %6.2f %5.0f %%" % (n_label, class_label(cls), len(v), math.exp(v.mean()),
                                                             100.0 * np.mean(np.abs(v) < math.log(2.0))))

if __name__ == "__main__":
    main()
