#include "sweep/cost_model.hpp"

#include <algorithm>
#include <cmath>

#include "engines/engine_registry.hpp"
#include "model/chain_parameters.hpp"

namespace granchain {

namespace {

// `/usr/bin/python3 bench/fit_cost_model.py --runs before.txt --runs current.txt --runs small.txt@1.66
// --runs dec1.txt@1.57 --seeds odd` (2026-12-01; the lists as docs/benchmarks.md, "A cost model that
// knows k", queries them): whole runs with their stored CPU time at k <= 1e10, the runs with odd
// seeds fit and the even ones check (1040 of 1047 within a factor of 2). The exact engine as it is
// since 2026-11-27 for N >= 50 (the paper's N = 50 ... 150 and the columns of N = 200 ... 1000), the
// engine of 2026-11-24 for the paper preset's N = 10 ... 50; a sweep of N = 3 ... 6 and the replicas
// of N = 100 and 150 on the power-law side at k = 1e7 ... 1e9 (today's engine) were timed on
// machines 1.66 and 1.57 times slower (bench/machine_factor.sh), their times divided by it. Order of
// exact_log_rate's features; the 14th is the power of N beyond the box (N^2.29 from the rate of
// N = 150 at the column's own N (1 - e)), the 15th and 16th let a collapsing column's cost bend in k
// with N (the condensed layer's events), the last two are the power-law side's line in x.
constexpr int kFeatures = 18;
constexpr double kExactCoefficients[kFeatures] = {
    -12.9146, 1.00692,  0.210062,  -1.77016,   2.2079,    -0.407345, -0.103172, 0.104713, -0.00698904,
    -0.215018, -0.21001, 0.0730899, -0.452079, 2.28906, -0.0344333, 0.105649,  4.60179,  -1.00039};
constexpr double kCalibratedNMin = 3, kCalibratedNMax = 150, kDecadesAbove1e5 = 5;
const double kXMax = std::log1p(kCalibratedNMax * 0.9);  // the largest c of the box: N = 150 at e = 0.1
// The polynomial in x stops at N (1 - e) = 30; beyond it, on the power-law side, ln(rate) is a line
// in x with a slope that depends on N (a cubic through the smaller columns turned over there and
// made N = 150 at e = 0.1 2.5 times cheaper than at e = 0.4, whose measured costs hardly differ).
const double kXPolynomialMax = std::log1p(30.0);
constexpr double kRunOverheadSeconds = 2e-3;  // set-up and the blocking analysis of a short run
// `/usr/bin/python3 bench/fit_high_k_cost.py data/paper/paper.db data/columns/columns.db
// data/columns/long_windows.db` (2026-12-07): above k = 1e10 the rate of k = 1e10 grows by exp(s)
// per decade of k, s = P(x) + delta w(c) ln(max(N, 100) / 100), c = N (1 - e), x = ln(1 + c):
// P piecewise linear in x between its values at the knots c = 1.2 ... 35 (x clamped to them),
// w = 1 for c <= 3 falling to 0 at c = 5. Fitted on the 1061 runs of the 155 columns with two or
// more k >= 1e10 (N = 10 ... 1000, k = 1e10 ... 1e30), one free offset per column. A collapsing column's collisions grow like
// k^alpha: s = 0.46 at c >= 35 (the columns of N = 50 ... 300 there: 0.42 ... 0.68 each), 0.52 at
// c = 10; an uncollapsing one's cost falls slightly, s = -0.09 at c <= 2.8 for N <= 100, and more
// slowly in large columns (-0.056 at N = 300, -0.016 at 1000, as the stored columns fall by about
// 0.05 and hardly at all), a fall measured only up to k = 1e15 and not extrapolated beyond it: the
// fit counts a falling column's decades up to five, as the model does.
constexpr int kAboveKKnotCount = 7;
constexpr double kAboveKKnotsC[kAboveKKnotCount] = {1.2, 2.0, 2.8, 3.5, 5.0, 10.0, 35.0};
constexpr double kAboveKKnots[kAboveKKnotCount] = {-0.093, -0.092, -0.096, 0.006, 0.081, 0.520, 0.458};
constexpr double kAboveKLargeN = 0.033;
constexpr double kDecadesOfFallMeasured = 5;

// s, the growth of ln(rate) per decade of k above 1e10.
double growth_per_decade_above_box_k(double N, double e) {
  const double c = N * (1.0 - e);
  const double x = std::clamp(std::log1p(c), std::log1p(kAboveKKnotsC[0]), std::log1p(kAboveKKnotsC[kAboveKKnotCount - 1]));
  double p = kAboveKKnots[kAboveKKnotCount - 1];
  for (int j = 0; j + 1 < kAboveKKnotCount; ++j) {
    const double x0 = std::log1p(kAboveKKnotsC[j]), x1 = std::log1p(kAboveKKnotsC[j + 1]);
    if (x <= x1) {
      p = kAboveKKnots[j] + (kAboveKKnots[j + 1] - kAboveKKnots[j]) * (x - x0) / (x1 - x0);
      break;
    }
  }
  const double w = std::clamp((5.0 - c) / 2.0, 0.0, 1.0);
  return p + kAboveKLargeN * w * std::log(std::max(N, 100.0) / 100.0);
}

// ln of what the rate gains from k = 1e10 to k (0 at k <= 1e10).
double log_growth_above_box_k(double N, double e, double k) {
  const double decades = std::log10(k) - (5.0 + kDecadesAbove1e5);
  if (decades <= 0.0) return 0.0;
  const double s = growth_per_decade_above_box_k(N, e);
  return s * (s < 0.0 ? std::min(decades, kDecadesOfFallMeasured) : decades);
}

// The features of bench/fit_cost_model.py, same order: below N = 3 the rate of N = 3 times N / 3.
double exact_log_rate(double N, double e, double k, double T0) {
  const double n = std::clamp(N, kCalibratedNMin, kCalibratedNMax);
  const double lN = std::log(n);
  const double xc = std::min(std::log1p(N * (1.0 - e)), kXMax);  // c = N (1 - e) of the column itself, within the box
  const double x = std::min(xc, kXPolynomialMax);
  const double h = xc - x;  // beyond N (1 - e) = 30: the power-law side's line in x
  const double lk = std::clamp(std::log10(k) - 5.0, 0.0, kDecadesAbove1e5);
  const double beyond = N > kCalibratedNMax ? std::log(N / kCalibratedNMax) : 0.0;
  const double f[kFeatures] = {1.0,     lN,          lN * lN,     x,      x * x,       x * x * x,
                               lk,      lk * x,      lk * x * x,  lk * lN, x * lN,     lk * lk,
                               std::log(T0), beyond, lk * lk * x, lk * x * lN, h,      h * lN};
  double s = 0.0;
  for (int j = 0; j < kFeatures; ++j) s += kExactCoefficients[j] * f[j];
  return s + (N < n ? std::log(N / n) : 0.0) + log_growth_above_box_k(N, e, k);
}

// `/usr/bin/python3 bench/fit_plate_cost.py data/drives/paper.db data/drives/quick.db` (2026-11-27):
// a vibrating plate costs the thermal floor's prediction times
//   exp(a_drive + b_drive lk + c ln(N / 25) + d x + g x lk + h lk^2),
// lk = log10 k - 6 in [-2, 4], x = ln(1 + N (1 - e)) in [0, ln 7] (clamped: the fitted range),
// fitted on 2109 plate runs of the drives figures' grids (N = 10 ... 100, k = 1e4 ... 1e10, omega =
// 10) against the thermal runs of the same points. Within a factor of 2 for 96 % of the runs at
// k <= 1e6, 82 % at 1e8 and 35 % at 1e10, where the cost follows how long the column rests on the
// plate, a property of the trajectory (docs/benchmarks.md).
constexpr double kPlateCost[10] = {-0.08323, -0.4078, 0.05758, -0.3065, -0.2968,
                                   -0.1809,  -0.2712, 0.05679, 0.3674,  0.04823};

double plate_cost_factor(const DriveSpec& drive, double N, double e, double k) {
  if (!drive.plate()) return 1.0;
  const int which = drive.kind == DriveKind::Sine ? 0 : drive.kind == DriveKind::Sawtooth ? 1 : 2;
  const double lk = std::clamp(std::log10(k) - 6.0, -2.0, 4.0);
  const double x = std::clamp(std::log1p(N * (1.0 - e)), 0.0, std::log(7.0));
  return std::exp(kPlateCost[which] + kPlateCost[3 + which] * lk + kPlateCost[6] * std::log(N / 25.0) + kPlateCost[7] * x +
                  kPlateCost[8] * x * lk + kPlateCost[9] * lk * lk);
}

}  // namespace

double estimate_cost_seconds(const RunSpec& s) {
  const ChainParameters& p = s.params;
  const double time = s.T + s.transient;
  if (engine_info(s.engine.kind).hard_spheres) {
    double seconds = kRunOverheadSeconds + 3e-7 * p.N * time * (10.0 + 120.0 * (1.0 - p.e));
    if (s.engine.start_k > 0) {  // the exact engine runs the transient at start_k
      RunSpec soft = s;
      soft.engine.kind = EngineKind::Exact;
      soft.params.k = s.engine.start_k;
      soft.T = 0.0;
      seconds += estimate_cost_seconds(soft);
    }
    return seconds;
  }
  if (s.engine.kind == EngineKind::Exact)
    return kRunOverheadSeconds + time * std::exp(exact_log_rate(p.N, p.e, p.k, p.kT0)) * plate_cost_factor(s.drive, p.N, p.e, p.k);
  const double steps = time * s.engine.dt_factor / contact_law(p).tau_c;
  return kRunOverheadSeconds + steps * (5e-9 * p.N + 4e-8);
}

}  // namespace granchain
