#include "analysis/collision_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "analysis/collapse_regimes.hpp"

namespace granchain::analysis {

std::vector<double> system_gaps(const std::vector<Collision>& c) {
  std::vector<double> g;
  for (std::size_t n = 1; n < c.size(); ++n) g.push_back(c[n].t_begin - c[n - 1].t_end);
  return g;
}

std::vector<double> pair_gaps(const std::vector<Collision>& c) {
  std::map<int, double> last_end;
  std::vector<double> g;
  for (const Collision& x : c) {
    const auto it = last_end.find(x.pair);
    if (it != last_end.end()) g.push_back(x.t_begin - it->second);
    last_end[x.pair] = x.t_end;
  }
  return g;
}

double mean_pair_log_ratio(const std::vector<Collision>& c, std::size_t first, std::size_t last) {
  std::map<int, std::vector<const Collision*>> by_pair;
  for (std::size_t n = first; n <= last && n < c.size(); ++n) by_pair[c[n].pair].push_back(&c[n]);
  double sum = 0;
  int pairs = 0;
  for (const auto& [pair, list] : by_pair) {
    if (list.size() < 3) continue;
    double s = 0;
    for (std::size_t j = 2; j < list.size(); ++j)
      s += std::log((list[j]->t_begin - list[j - 1]->t_end) / (list[j - 1]->t_begin - list[j - 2]->t_end));
    sum += s / static_cast<double>(list.size() - 2);
    ++pairs;
  }
  return pairs > 0 ? sum / pairs : std::numeric_limits<double>::quiet_NaN();
}

int particles_involved(const std::vector<Collision>& c, std::size_t first, std::size_t last) {
  std::set<int> p;
  for (std::size_t n = first; n <= last && n < c.size(); ++n) {
    if (c[n].pair > 0) p.insert(c[n].pair);
    p.insert(c[n].pair + 1);
  }
  return static_cast<int>(p.size());
}

std::vector<CollapseEvent> collapse_events(const std::vector<Collision>& c, double max_gap, std::size_t min_collisions) {
  std::vector<CollapseEvent> out;
  std::size_t start = 0;
  for (std::size_t n = 1; n <= c.size(); ++n) {
    const bool joined = n < c.size() && c[n].t_begin - c[n - 1].t_end < max_gap;
    if (joined) continue;
    const std::size_t count = n - start;  // collisions start .. n-1
    if (count >= min_collisions && count > 0) out.push_back({start, count, particles_involved(c, start, n - 1)});
    start = n;
  }
  return out;
}

std::vector<Cascade> cascades(const std::vector<EventSpan>& events, double max_wait) {
  std::vector<Cascade> out;
  for (std::size_t n = 0; n < events.size(); ++n) {
    if (n == 0 || events[n].begin - events[n - 1].end >= max_wait) out.push_back({n, 0});
    ++out.back().events;
  }
  return out;
}

std::vector<double> collisions_before_remaining(const std::vector<Collision>& c, double t_star, const std::vector<double>& taus) {
  std::vector<double> out;
  for (double tau : taus) {
    std::size_t n = 0;
    while (n < c.size() && t_star - c[n].t_begin >= tau) ++n;
    out.push_back(static_cast<double>(n));
  }
  return out;
}

ShrinkFit fit_remaining_time(const std::vector<Collision>& c, double t_star, double tau_lo, double tau_hi) {
  std::vector<DataPoint> geo, pow;
  ShrinkFit f;
  for (std::size_t n = 0; n < c.size(); ++n) {
    const double tau = t_star - c[n].t_begin;
    if (tau < tau_lo || tau > tau_hi) continue;
    if (geo.empty()) f.first = n;
    f.last = n;
    const double idx = static_cast<double>(n + 1);
    geo.push_back({idx, std::log(tau), 1.0});
    pow.push_back({std::log(idx), std::log(tau), 1.0});
  }
  f.points = static_cast<int>(geo.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (f.points < 4) {
    f.ln_q = f.ln_q_error = f.rms_geometric = f.beta = f.beta_error = f.rms_power = nan;
    return f;
  }
  // With unit errors chi^2 is the sum of squared residuals; fit_polynomial scales its errors by
  // sqrt(chi^2/dof) only upward, so the ordinary least-squares errors take the rest of the factor.
  const PolynomialFit g = fit_polynomial(geo, 1), p = fit_polynomial(pow, 1);
  const double m = static_cast<double>(f.points);
  const auto ols_error = [](const PolynomialFit& fit) { return fit.error[1] * std::sqrt(std::min(1.0, fit.chi2 / fit.dof)); };
  f.ln_q = g.coef[1];
  f.ln_q_error = ols_error(g);
  f.rms_geometric = std::sqrt(g.chi2 / m);
  f.beta = 1.0 - p.coef[1];
  f.beta_error = ols_error(p);
  f.rms_power = std::sqrt(p.chi2 / m);
  return f;
}

}  // namespace granchain::analysis
