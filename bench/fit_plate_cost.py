#!/usr/bin/python3
"""Calibrates the vibrating plates' factor of the exact engine's cost model (src/sweep/cost_model.cpp)
on stores that hold the same points on the thermal floor and on the plates (the drives figures'
grids, `granchain reproduce --figure drives`).

The model: a plate run costs the thermal floor's prediction times exp(f), with
    f = a_drive + b_drive lk + c ln(N / 25) + d x + g x lk + h lk^2,
    lk = log10 k - 6 clamped to [-2, 4] (k = 1e4 ... 1e10), x = ln(1 + N (1 - e)) clamped to [0, ln 7]
(the paper's scaling variable N (1 - e), up to the grids' largest 6), fitted by least squares on
ln(CPU time of the plate run / CPU time of the thermal run with the same N, e, k, T and T0), runs
under 0.05 s of CPU left out (their time is mostly the fixed overhead). A condensed column rests on
the plate, and the cluster resting there is searched as a whole at every event (docs/benchmarks.md):
hence the terms in x and x lk.

    /usr/bin/python3 bench/fit_plate_cost.py data/drives/paper.db data/drives/quick.db

prints the coefficients as a C++ initialiser, then the held-out check (fitted on the runs with odd
store ids, tested on the even ones) and the whole fit's residuals per drive and per decade of k:
root-mean-square in ln and how many runs the factor predicts within a factor of 2.
"""
import math
import sqlite3
import sys

import numpy as np

DRIVES = ("sine", "sawtooth", "quadratic")
LK_RANGE = (-2.0, 4.0)
X_MAX = math.log(7.0)


def features(drive, N, e, k):
    lk = min(max(math.log10(k) - 6.0, LK_RANGE[0]), LK_RANGE[1])
    x = min(max(math.log1p(N * (1.0 - e)), 0.0), X_MAX)
    one = [1.0 if drive == d else 0.0 for d in DRIVES]
    return one + [lk * o for o in one] + [math.log(N / 25.0), x, x * lk, lk * lk]


def load(path):
    con = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
    rows = con.execute("SELECT coalesce(drive, 'thermal'), N, e, k, T, T0, cpu_seconds, id FROM runs "
                       "WHERE engine = 'exact' AND cpu_seconds IS NOT NULL").fetchall()
    thermal = {(N, round(e, 12), k, T, T0): cpu for d, N, e, k, T, T0, cpu, _ in rows if d == "thermal"}
    out = []
    for d, N, e, k, T, T0, cpu, rid in rows:
        t = thermal.get((N, round(e, 12), k, T, T0))
        if d == "thermal" or t is None or cpu < 0.05 or t < 0.05:
            continue
        out.append((d, N, e, k, math.log(cpu / t), rid))
    return out


def summary(label, r, mask):
    if not mask.any():
        return
    print("%-22s %5d runs: rms %.2f in ln, mean %+.2f, %.0f %% within a factor of 2" %
          (label, mask.sum(), r[mask].std(), r[mask].mean(), 100 * np.mean(np.abs(r[mask]) < math.log(2))))


def main(argv):
    if len(argv) < 2:
        sys.stderr.write(__doc__)
        return 2
    runs = [row for path in argv[1:] for row in load(path)]
    X = np.array([features(d, N, e, k) for d, N, e, k, _, _ in runs])
    y = np.array([ratio for *_, ratio, _ in runs])
    ids = np.array([rid for *_, rid in runs])
    drives = np.array([d for d, *_ in runs])
    decades = np.array([round(math.log10(k)) for _, _, _, k, _, _ in runs])
    coef = np.linalg.lstsq(X, y, rcond=None)[0]
    print("// a (sine, sawtooth, quadratic), b (same order), c, d, g, h: %d plate runs" % len(y))
    print("constexpr double kPlateCost[10] = {%s};" % ", ".join("%.4g" % c for c in coef))
    odd = ids % 2 == 1
    held = y[~odd] - X[~odd] @ np.linalg.lstsq(X[odd], y[odd], rcond=None)[0]
    summary("held out (even ids)", held, np.ones(len(held), bool))
    r = y - X @ coef
    for d in DRIVES:
        summary(d, r, drives == d)
    for dec in sorted(set(decades)):
        summary("k = 1e%d" % dec, r, decades == dec)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
