#pragma once
// What a driven-column run costs: seconds of one core of the development machine, used to start
// the longest points first, for the ETA of sweeps and for the cost a dry run or
// `reproduce --print-sweeps` announces. Calibrated on timed runs (docs/benchmarks.md, "A cost model
// that knows k"), not a physical law; another machine scales it by a constant.
#include "simulation/driven_run.hpp"

namespace granchain {

// Seconds for the whole run (transient + T), the run's fixed overhead included.
//  - exact engine: ln(seconds per unit time) is a quadratic-to-cubic form in ln N, x =
//    ln(1 + N (1 - e)) (the paper's scaling variable N (1 - e): the uncollapsing regime is
//    x < ln(1 + A), A ~ 2.6), log10 k and ln k_B T0, the polynomial in x up to N (1 - e) = 30 and a
//    line in x beyond it (the power-law side), fitted by bench/fit_cost_model.py on the CPU time of
//    1045 whole runs at k <= 1e10 (N = 3 ... 1000; 1040 of the 1047 held-out runs within a factor
//    of 2). N is held in the box 3 <= N <= 150 and k in 1e5 ... 1e10: beyond N = 150 the
//    rate of N = 150 at the column's own N (1 - e) is scaled by (N / 150)^2.29, fitted with the rest
//    on runs of N = 200 ... 1000; beyond k = 1e10 the rate of k = 1e10 times exp(s) per decade,
//    s piecewise linear in ln(1 + N (1 - e)): about -0.09 at N (1 - e) <= 2.8 for N <= 100 (a fall
//    that slows in larger columns: -0.016 at N = 1000), 0.08 at 5, 0.52 at 10 and 0.46 from 35 on
//    (the collisions of a collapsing column grow like k^alpha), fitted by bench/fit_high_k_cost.py on the stored runs up to
//    k = 1e30 (95 % of 874 within a factor of 2, 73 % with k held at 1e10). Above a vibrating
//    plate: times a factor of the drive, k, N and N (1 - e) fitted by bench/fit_plate_cost.py
//    (about 0.5-1.4 at k = 1e5, 1-5 at 1e8 and 1.3-17 at 1e10 for N = 25).
//  - reference engines: (5e-9 N + 4e-8) s per step of the whole column, dt = tau_c / dt-factor
//    (measured: 4.8e-9 .. 2.2e-8 s per particle step from N = 50 down to N = 3).
//  - hard-sphere engine: not calibrated; about 3e-7 s per collision with a guessed collision
//    rate of 10 + 120 (1 - e) per particle and unit time; with --start-k, plus the exact engine's
//    transient at that k.
double estimate_cost_seconds(const RunSpec& spec);

}  // namespace granchain
