#pragma once
// From n_coll(k) to the paper's regimes (Sec. III.C): weighted fits of n_coll = a + b log10 k and
// n_coll = c k^alpha, the convex/concave test against log k, the critical restitutions e_c1
// (where b vanishes) and e_c2 (the convex/concave boundary), and the fits (1 - e_c) = A/N and
// alpha = p log10 N + q (Eq. alphafit). Every result carries a standard error.
#include <cmath>
#include <string>
#include <vector>

namespace granchain::analysis {

// One measured point: x, y and the standard error of y (> 0).
struct DataPoint {
  double x = 0, y = 0, error = 0;
};

// Weighted least-squares polynomial y = sum_j coef[j] x^j (degree 1 or 2), weights 1/error^2.
// Errors are from the covariance matrix; when chi^2/dof > 1 they are multiplied by
// sqrt(chi^2/dof) (the scatter says the stated errors are too small), never shrunk.
struct PolynomialFit {
  std::vector<double> coef, error;
  double chi2 = 0;
  int dof = 0;
  double covariance01 = 0;  // cov(coef[0], coef[1]) after the same scaling
};
PolynomialFit fit_polynomial(const std::vector<DataPoint>& points, int degree);

// n_coll = a + b log10 k over the given points (x = k): b is collisions per particle and unit
// time gained per decade of k (Eq. b(e,N) with log = log10).
struct LogFit {
  double a = 0, a_error = 0, b = 0, b_error = 0, chi2 = 0;
  int dof = 0;
};
LogFit fit_log_k(const std::vector<DataPoint>& n_coll_of_k);

// n_coll = c k^alpha, fitted as ln n_coll = ln c + alpha ln k with errors error/n_coll.
struct PowerFit {
  double c = 0, c_error = 0, alpha = 0, alpha_error = 0, chi2 = 0;
  int dof = 0;
};
PowerFit fit_power_k(const std::vector<DataPoint>& n_coll_of_k);

enum class Regime { Uncollapsing, Logarithmic, PowerLaw };
const char* regime_name(Regime r);  // "uncollapsing", "logarithmic", "power-law"

// The classification of one (N, e) from n_coll(k) over the asymptotic range (points with
// k >= k_min), by these criteria (z = 2 standard errors):
//   uncollapsing: the slope b of a + b log10 k is not above zero by z errors, or the last decade's
//                 own slope (between the two largest k) is not: a converging n_coll (approaching
//                 its limit as k^-1/2) has b > 0 over any finite range, but its increments die out;
//   power-law:    b > 0 by z errors and n_coll is convex against log10 k (the curvature c of
//                 a + b x + c x^2 is above zero by z errors): it grows faster than log k;
//   logarithmic:  b > 0 by z errors and not convex.
// Needs at least 3 points (with 3 the curvature is their second difference, and convexity is never
// claimed: power-law asks for 4).
struct Classification {
  Regime regime = Regime::Uncollapsing;
  LogFit log_fit;
  PowerFit power_fit;
  double curvature = 0, curvature_error = 0;  // c of a + b x + c x^2, x = log10 k
  double last_slope = 0, last_slope_error = 0;  // (n(k2) - n(k1)) / log10(k2/k1), the two largest k
};
Classification classify(const std::vector<DataPoint>& n_coll_of_k, double k_min = 0.0, double z = 2.0);

// A critical value with its standard error, or a bracket where it was located between two grid
// points (e_c2), and how it was found.
struct CriticalValue {
  double value = 0, error = 0;
  double low = 0, high = 0;  // bracket (equal to value when not bracketed)
  bool found = false;
  std::string method;
  // Located only to the grid (a bracket between two grid points, or a zero interpolated between
  // them): part of the error is the grid's rounding, (high - low) / sqrt 12, shared by every N of a
  // grid e = 1 - c/N.
  bool grid_rounded = false;
};

// e_c1 for one N from b(e) (x = e, y = b; uncollapsing e enter with b = 0): near e_c1 the paper
// finds b ~ ((1-e) - A/N)^2 (Eq. b_e_N), so sqrt(b) is linear in e and vanishes at e_c1. Fits
// sqrt(b) = s (e_c1 - e) (weighted, error of sqrt(b) = error_b / (2 sqrt b)) over the points with b
// > z errors above zero that lie within `window` below the largest such e (e_max), and returns the
// root with its propagated error. Found only when the root lies in [e_max, e_max + window], below 1,
// and inside the grid (the largest e of b_of_e is at or above it).
CriticalValue e_c1_from_b(const std::vector<DataPoint>& b_of_e, double window = 0.05, double z = 2.0);

// e_c2 for one N: the boundary between the power-law (convex) and the logarithmic regimes along e.
// Returns the bracket between the largest e classified power-law and the next larger e of the
// grid, value its midpoint and error half its width. Not found if no e is power-law or none above.
CriticalValue e_c2_from_regimes(const std::vector<double>& e, const std::vector<Regime>& regimes);
// e_c2 as the paper reads it off its figures: where the curvature of n_coll against log10 k
// changes sign, convex below, concave above (pass the collapsing curves: x = e, y = curvature).
// Scanning down from the largest e, the first e with a positive curvature and the e above it
// bracket the change (low, high); a weighted straight line through the curvatures within
// half_width of the bracket gives the zero and, from its covariance, the error. On a grid too
// coarse for three such points (fig6's e = 1 - c/N), or where that line's zero falls outside them
// (an extrapolation), the zero is interpolated linearly between the two bracketing curvatures,
// its error their propagated errors and the bracket's width / sqrt 12 in quadrature.
// A bracket wider than max_gap (a hole in the grid) locates nothing, and without a sign change
// nothing is found; a line through the points near it that does not fall with e also falls back to
// the interpolation. Unlike e_c2_from_regimes this asks for no significance, so it does not move
// down to where the curvature becomes resolvable.
CriticalValue e_c2_from_curvature_sign(const std::vector<DataPoint>& curvature_of_e, double half_width = 0.0061,
                                       double max_gap = INFINITY);

// (1 - e_c) = A / N through the origin in 1/N, weighted by the errors of e_c (Eq. e-fit).
struct InverseNFit {
  double A = 0, A_error = 0, chi2 = 0;
  int dof = 0;
};
InverseNFit fit_inverse_n(const std::vector<double>& N, const std::vector<CriticalValue>& e_c);

// alpha = p log10 N + q (Eq. alphafit), weighted.
struct LineFit {
  double slope = 0, slope_error = 0, intercept = 0, intercept_error = 0, chi2 = 0;
  int dof = 0;
};
LineFit fit_alpha_vs_log10_n(const std::vector<DataPoint>& alpha_of_n);

// Fig. logfitbX: near e_c1 the log slope obeys b(e, N) / N^{5/2} = C X^s with X = (1 - e) - A/N,
// the paper finding s = 2, C = 1.5 at A = 2.6 (Eq. b_e_N). Fitted as ln(b / N^{5/2}) = ln C + s ln X
// (weighted, the error of ln b being b_error / b) over the points with X > 0 and b above zero by z
// errors; C2 is the prefactor with s held at 2 (weighted mean of ln(b / N^{5/2} / X^2)). Errors are
// scaled by sqrt(chi^2/dof) when that exceeds 1.
struct ScalingPoint {
  int N = 0;
  double e = 0, b = 0, b_error = 0;
};
struct ScalingCollapseFit {
  double A = 0;
  int points = 0;  // used in the fits
  double slope = 0, slope_error = 0, prefactor = 0, prefactor_error = 0, chi2 = 0;
  int dof = 0;
  double C2 = 0, C2_error = 0, chi2_C2 = 0;
};
// Throws std::invalid_argument with fewer than 3 usable points.
ScalingCollapseFit fit_scaling_collapse(const std::vector<ScalingPoint>& points, double A, double z = 2.0);

// The mean of several alphas (Table 1's alpha bar) with its standard error: the larger of the
// propagated error and the scatter's standard error of the mean.
struct Mean {
  double value = 0, error = 0;
};
Mean mean_exponent(const std::vector<DataPoint>& alphas);

// The local exponent between neighbouring k of n_coll(k) (k ascending): alpha = ln(n2/n1) /
// ln(k2/k1), error from the two relative errors. A global power fit averages these; their trend
// with k says whether the power law holds (constant) or the slope drifts.
struct LocalExponent {
  double k1 = 0, k2 = 0, alpha = 0, error = 0;
};
std::vector<LocalExponent> local_exponents(const std::vector<DataPoint>& n_coll_of_k);
// Per interval of k, the weighted mean over several curves' local exponents (intervals matched by
// k1, k2; those missing in some curve are averaged over the others). Error: the larger of the
// propagated one and the scatter's standard error, as mean_exponent.
std::vector<LocalExponent> mean_local_exponents(const std::vector<std::vector<LocalExponent>>& curves);

}  // namespace granchain::analysis
