#!/usr/bin/python3
"""Calibrates the vibrating plates' factor of the exact engine's cost model (src/sweep/cost_model.cpp)
on a store that holds the same points on the thermal floor and on the plates (the drives figures'
grid, `granchain reproduce --figure drives`).

The model: a plate run costs the thermal floor's prediction times
    exp(a_drive + b (log10 k - 6) + c ln(N / 25)),
fitted by least squares on ln(CPU time of the plate run / CPU time of the thermal run with the same
N, e, k, T and T0), runs under 0.05 s of CPU left out (their time is mostly the fixed overhead).
One b and c for all plates, an a per drive.

    /usr/bin/python3 bench/fit_plate_cost.py data/drives/quick.db

prints the coefficients as a C++ initialiser, the root-mean-square residual and how many runs the
factor predicts within a factor of 2, per drive.
"""
import math
import sqlite3
import sys

import numpy as np

DRIVES = ("sine", "sawtooth", "quadratic")


def main(argv):
    if len(argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    con = sqlite3.connect("file:%s?mode=ro" % argv[1], uri=True)
    rows = con.execute("SELECT coalesce(drive, 'thermal'), N, e, k, T, T0, cpu_seconds FROM runs "
                       "WHERE engine = 'exact' AND cpu_seconds IS NOT NULL").fetchall()
    thermal = {(N, round(e, 12), k, T, T0): cpu for d, N, e, k, T, T0, cpu in rows if d == "thermal"}
    X, y, which = [], [], []
    for d, N, e, k, T, T0, cpu in rows:
        t = thermal.get((N, round(e, 12), k, T, T0))
        if d == "thermal" or t is None or cpu < 0.05 or t < 0.05:
            continue
        X.append([1.0 if d == x else 0.0 for x in DRIVES] + [math.log10(k) - 6, math.log(N / 25)])
        y.append(math.log(cpu / t))
        which.append(d)
    X, y = np.array(X), np.array(y)
    coef = np.linalg.lstsq(X, y, rcond=None)[0]
    r = y - X @ coef
    print("// a (sine, sawtooth, quadratic), b, c: %d plate runs" % len(y))
    print("constexpr double kPlateCost[5] = {%s};" % ", ".join("%.4g" % c for c in coef))
    for d in DRIVES:
        m = np.array([w == d for w in which])
        print("%-9s %4d runs: rms %.2f in ln, %.0f %% within a factor of 2" %
              (d, m.sum(), r[m].std(), 100 * np.mean(np.abs(r[m]) < math.log(2))))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
