#!/usr/bin/python3
"""Calibrates the exact engine's cost model (src/sweep/cost_model.cpp) on points timed by
bench/paper_cost.sh --list FILE.

The model: ln(seconds per unit of simulated time) = sum_j c_j f_j(N, e, k, T0), with the features
of cost_model.cpp (FEATURES below, in the same order), fitted by weighted least squares. Points
whose long run took under 0.05 s weigh 0.05: their timing is mostly the run's fixed overhead.
Each point's measured rate is the settled one, (long - short) / (LONG - SHORT), or the mean over the
long run where that is larger (the difference of two short timings is noise for cheap points).

    /usr/bin/python3 bench/fit_cost_model.py [sample.txt ...] [--short 10 --long 40 --settle 40]
                                             [--runs runs.txt ...] [--seeds odd|even|all]

--runs (repeatable) adds whole runs from a results store (bench/cost_model_check.sh --list): their
time (CPU time where stored) over T + transient is the rate, free of the start-up effects that make
the sample's millisecond timings unreliable; --seeds keeps only those with odd or even seeds, so
that the others can check the model.

prints the coefficients as a C++ initialiser and how many points the model predicts within a
factor of 2.
"""
import argparse
import math

import numpy as np


def features(N, e, k, T0):
    """The model's features; keep in step with exact_features() in src/sweep/cost_model.cpp."""
    lN = math.log(min(max(N, 3.0), 150.0))
    x = math.log1p(min(max(N, 3.0), 150.0) * (1.0 - e))
    lk = min(max(math.log10(k) - 5.0, 0.0), 5.0)
    return [1.0, lN, lN * lN, x, x * x, x ** 3, lk, lk * x, lk * x * x, lk * lN, x * lN, lk * lk, math.log(T0)]


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
        for line in open(runs):
            f = line.split()
            N, e, k, T0, T, tr, wall, seed = (float(f[0]), float(f[1]), float(f[2]), float(f[3]), float(f[4]),
                                              float(f[5]), float(f[7]), f[8])
            if a.seeds != "all" and (int(seed[-1]) % 2 == 1) != (a.seeds == "odd"):
                continue
            rows.append(features(N, e, k, T0))
            rates.append(wall / (T + tr))
            weights.append(1.0)
    X, y, w = np.array(rows), np.log(np.array(rates)), np.array(weights)
    coef, *_ = np.linalg.lstsq(X * w[:, None], y * w, rcond=None)
    ratio = np.exp(X @ coef - y)
    timed = w == 1.0
    within = (ratio > 0.5) & (ratio < 2.0)
    print("// %d points, %d timed above 0.05 s" % (len(y), timed.sum()))
    print("// predicted / measured within a factor of 2: %d of %d (all), %d of %d (timed above 0.05 s);"
          % (within.sum(), len(y), within[timed].sum(), timed.sum()))
    print("// range over those: %.2f .. %.2f" % (ratio[timed].min(), ratio[timed].max()))
    print("constexpr double kExactCoefficients[%d] = {%s};" % (len(coef), ", ".join("%.6g" % c for c in coef)))


if __name__ == "__main__":
    main()
