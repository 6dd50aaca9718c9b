// `granchain reproduce --figure intervals` (group `beyond`): the collision sequences of free-space
// collapses (Sec. III.D), to see where n_tot ~ k^alpha comes from (paper Summary: intervals that
// shrink as a power of the collision number rather than geometrically, as for three bodies).
//   Hard spheres (k = infinity), up to the detected collapse: the remaining time tau_n = t* - t_n
//   against n, geometric or a power of n (analysis/collision_sequence); the count n(tau) of
//   collisions before the sequence comes within tau of the collapse, the count a cut-off at tau
//   leaves, set against k through tau = tau_c(k); the particles of the final collapse.
//   Soft spheres at large k: the gaps between collisions in units of tau_c, and the collapse events
//   (runs of collisions less than 10 tau_c apart): how many per launch, how many collisions and
//   particles each, against k.
// The sequences are recomputed on each call (minutes at most); nothing is stored.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "analysis/asymptotic_forms.hpp"
#include "analysis/blocking.hpp"
#include "analysis/collision_sequence.hpp"
#include "reproduce/figures.hpp"
#include "simulation/collapse_run.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain {

namespace {

using analysis::Collision;

constexpr int kN = 25;
constexpr double kEventGap = 10.0;  // a collapse event: successive gaps below 10 tau_c
constexpr std::size_t kEventMin = 3;
constexpr int kSpeedDecades = 16;  // approach speeds of collapse events binned by decade down to 1e-16
constexpr int kSpeedColumns = 14;  // the decades the report shows, 1e-1 .. 1e-14
constexpr double kCascadeWait = 1000.0;  // a cascade: events less than 1000 tau_c apart
constexpr int kWaitDecades = 10;        // waits between events (>= 10 tau_c by the event rule) by decade of wait / tau_c: 1e1, ..., >= 1e10

std::vector<Collision> to_sequence(const std::vector<CollisionRecord>& recs) {
  std::vector<Collision> c;
  c.reserve(recs.size());
  for (const auto& r : recs) c.push_back({r.t_begin, r.t_end, r.i});
  return c;
}

double median(std::vector<double> x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2), x.end());
  return x[x.size() / 2];
}

// One section of the report and its part of the figure's data.
struct Section {
  nlohmann::json json;
  std::string markdown;
};

Section hard_sequences(double e, int launches, const ReproduceFlags& o) {
  std::vector<double> taus;
  for (int j = 2; j <= 16; ++j) taus.push_back(std::pow(10.0, -0.5 * j));  // 1e-1 .. 1e-8
  CollapseSpec spec = free_space_spec(kN, e, std::numeric_limits<double>::infinity(), launches, o);
  spec.engine.kind = EngineKind::Hard;
  const std::size_t last = spec.engine.hard.collapse_collisions;
  std::vector<std::vector<double>> counts;  // per collapsed launch, n(tau)
  std::vector<double> ln_q, beta, particles;
  std::vector<double> ln_q_pair;  // per launch, the mean per-pair log ratio over 1e-8 <= tau_n <= 1e-2
  int geometric_closer = 0, fitted = 0;
  nlohmann::json samples = nlohmann::json::array();
  run_collapse(spec, [&](const std::vector<CollisionRecord>& recs) {
    if (recs.size() < last + 4) return;  // ended without a collapse (counted below from the result)
    const std::vector<Collision> seq = to_sequence(recs);
    const double t_star = seq.back().t_begin;  // within collapse_time of the collapse
    counts.push_back(analysis::collisions_before_remaining(seq, t_star, taus));
    particles.push_back(analysis::particles_involved(seq, seq.size() - last, seq.size() - 1));
    const analysis::ShrinkFit f = analysis::fit_remaining_time(seq, t_star, 1e-8, 1e-2);
    if (f.points >= 4) {
      ++fitted;
      geometric_closer += f.rms_geometric < f.rms_power;
      ln_q.push_back(f.ln_q);
      const double r = analysis::mean_pair_log_ratio(seq, f.first, f.last);
      if (std::isfinite(r)) ln_q_pair.push_back(r);
      beta.push_back(f.beta);
    }
    if (samples.size() < 4) {
      nlohmann::json s = {{"n", nlohmann::json::array()}, {"tau", nlohmann::json::array()}};
      for (std::size_t n = 0; n < seq.size(); ++n) {
        const double tau = t_star - seq[n].t_begin;
        if (tau < 1e-9) break;
        s["n"].push_back(n + 1);
        s["tau"].push_back(tau);
      }
      samples.push_back(s);
    }
  });
  Section out;
  const std::size_t R = counts.size();
  // The k whose contact duration is tau: tau_c is proportional to k^-1/2 at fixed e.
  const double tau_c_at_unit_k = contact_law(free_space_spec(kN, e, 1.0, 1, o).params).tau_c;
  std::vector<double> kq;
  for (double tau : taus) kq.push_back(std::pow(tau_c_at_unit_k / tau, 2));
  std::vector<double> n_mean(taus.size(), std::numeric_limits<double>::quiet_NaN()), n_err = n_mean;
  Eigen::MatrixXd C;
  std::vector<analysis::LocalExponent> local;  // d ln n / d ln k_tau, errors from the paired launches
  if (R >= 2) {
    n_mean = analysis::means(counts);
    C = analysis::covariance_of_means(counts);
    for (std::size_t i = 0; i < taus.size(); ++i) n_err[i] = std::sqrt(C(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)));
    local = analysis::local_exponents(kq, n_mean, C);
  }
  const auto [p_mean, p_err] = mean_and_error(particles);
  const double pmin = particles.empty() ? 0 : *std::min_element(particles.begin(), particles.end());
  const double pmax = particles.empty() ? 0 : *std::max_element(particles.begin(), particles.end());
  out.json = {{"e", e}, {"launches", launches}, {"collapsed", R}, {"tau", taus}, {"k_equiv", kq}, {"n", n_mean}, {"n_error", n_err},
              {"samples", samples}, {"particles", particles}, {"geometric_closer", geometric_closer}, {"fitted", fitted},
              {"median_q", std::exp(median(ln_q))}, {"median_beta", median(beta)}, {"median_q_pair", std::exp(median(ln_q_pair))}};
  out.json["local"] = local_exponents_json(local);
  std::string& md = out.markdown;
  md = fmt::format("\n### Hard spheres, e = {:g}: {} of {} launches collapse\n\n", e, R, launches);
  if (R < 2) {
    md += "Too few collapses to measure.\n";
    return out;
  }
  int n_star = 3;  // the fewest free particles that can collapse at e: e_c(n) > e (Sec. III.B's estimate)
  while (n_star < kN && theory::ec_free(n_star) <= e) ++n_star;
  md += fmt::format("Particles touched by the last {} collisions before the collapse was detected: mean {}, from {:g} to {:g}. The "
                    "fewest free particles that can collapse at this e, the least n with e_c(n) = tan²(π/4 (1 − 2/n)) > e "
                    "(Sec. III.B): n* = {} (e_c({}) = {:.4f}{}).\n\n",
                    last, plus_minus(p_mean, p_err, 1), pmin, pmax, n_star, n_star, theory::ec_free(n_star),
                    n_star > 3 ? fmt::format(", e_c({}) = {:.4f}", n_star - 1, theory::ec_free(n_star - 1)) : "");
  out.json["n_star"] = n_star;
  md += fmt::format("Approach to the collapse, tau_n = t* - t_n over 1e-8 ≤ tau_n ≤ 1e-2: in {} of {} launches a geometric sequence "
                    "(ln tau_n linear in n) fits with a smaller rms residual than a power of n (ln tau_n linear in ln n); median "
                    "ratio per collision q = {:.4f}, median exponent β = {:.2f} (intervals ~ n^-β). Per pair, the interval "
                    "between its successive collisions shrinks by a median factor {:.4f} from one to the next (geometric mean "
                    "over the pairs and collisions of each launch in the same range; q per collision to the power {:.2f}).\n\n",
                    geometric_closer, fitted, std::exp(median(ln_q)), median(beta), std::exp(median(ln_q_pair)),
                    median(ln_q_pair) / median(ln_q));
  md += "Collisions n(τ) before the sequence comes within τ of the collapse, with the k whose τ_c is τ:\n\n"
        "| τ | k with τ_c = τ | n(τ) | local exponent d ln n / d ln k to the next τ |\n|---|---|---|---|\n";
  for (std::size_t i = 0; i < taus.size(); ++i)
    md += fmt::format("| {:.3g} | {:.3g} | {} | {} |\n", taus[i], kq[i], plus_minus(n_mean[i], n_err[i], 1),
                      i < local.size() ? plus_minus(local[i].alpha, local[i].error, 3) : "");
  bool positive = true;
  for (std::size_t i = 0; i < taus.size(); ++i) positive = positive && n_err[i] > 0 && n_mean[i] > 0;
  if (positive) {
    std::vector<double> kk(kq.begin(), kq.end());
    const analysis::FormComparison c = analysis::compare_asymptotic_forms(kk, n_mean, C);
    md += "\nForms of n against k_τ (all τ, covariance from the launches):";
    for (const auto& f : c.fits)
      md += fmt::format(" {}: χ² = {:.1f} / {}, weight {:.2f};", analysis::form_name(f.form), f.chi2, f.dof, f.akaike_weight);
    md += fmt::format(" AICc prefers {}.\n", analysis::form_name(c.fits[static_cast<std::size_t>(c.best_aicc)].form));
    out.json["best_form"] = analysis::form_name(c.fits[static_cast<std::size_t>(c.best_aicc)].form);
  }
  return out;
}

struct SoftLaunch {
  double n = 0, events = 0, in_events = 0, particles = 0;  // particles: summed over events
  double cascades = 0;
};

// The ratio of two sums over launches, sum(a) / sum(b), and its error by the delta method.
std::pair<double, double> ratio_of_sums(const std::vector<double>& a, const std::vector<double>& b) {
  double sa = 0, sb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sa += a[i], sb += b[i];
  const double r = sb > 0 ? sa / sb : 0.0;
  std::vector<double> lin;
  for (std::size_t i = 0; i < a.size(); ++i) lin.push_back(sb > 0 ? (a[i] - r * b[i]) * static_cast<double>(a.size()) / sb : 0.0);
  return {r, mean_and_error(lin).second};
}

Section soft_sequences(double e, const std::vector<double>& ks, int launches, const ReproduceFlags& o) {
  Section out;
  out.json = {{"e", e}, {"launches", launches}, {"k", ks}, {"per_k", nlohmann::json::array()}};
  std::vector<double> edges;  // gap / tau_c, half decades from 1e-2 to 1e8
  for (int j = -4; j <= 16; ++j) edges.push_back(std::pow(10.0, 0.5 * j));
  std::string& md = out.markdown;
  md = fmt::format("\n### Soft spheres, e = {:g}, {} launches per k\n\n| k | n_tot | collapse events per launch | collisions per event | "
                   "particles per event | collisions in events | overlapping contacts |\n|---|---|---|---|---|---|---|\n",
                   e, launches);
  std::vector<double> ev_mean, ev_err, per_mean, per_err, casc_mean, casc_err, epc_mean, epc_err_v;
  std::string speed_rows, cascade_rows;
  for (double k : ks) {
    const CollapseSpec spec = free_space_spec(kN, e, k, launches, o);
    const double tau_c = contact_law(spec.params).tau_c;
    std::vector<SoftLaunch> L;
    std::vector<double> gap_hist(edges.size() + 1, 0.0), pair_hist(edges.size() + 1, 0.0), part_hist(kN + 1, 0.0);
    double overlapping = 0, gaps_total = 0;
    // Events by the decade of their approach speed, 1e-kSpeedDecades .. 1 (slower ones in the first bin).
    std::vector<double> speed_hist(kSpeedDecades + 1, 0.0), rebound, duration, wait;
    // The cluster an event leaves, read from the chain when its last contact has ended: the
    // kinetic energy of its particles' motion about their centre of mass over the approach energy
    // m u_a^2 / 4 of its first collision, and the sum of its gaps over u_a tau_c.
    std::vector<double> internal_energy, spread;
    // Successive events of one cascade: the next approach speed against the speed the previous
    // event left (log10 u_a(n+1) / u_r(n)) and against its approach speed; waits by decade.
    std::vector<double> next_over_left, next_over_approach, wait_hist(kWaitDecades, 0.0);
    const auto speed_bin = [&](double u) {
      const double d = u > 0 ? std::floor(std::log10(u)) : -kSpeedDecades;
      speed_hist[static_cast<std::size_t>(std::clamp(d + kSpeedDecades, 0.0, static_cast<double>(kSpeedDecades)))] += 1;
    };
    const auto bin = [&](std::vector<double>& h, double g) {
      if (g <= 0) return;
      const auto it = std::upper_bound(edges.begin(), edges.end(), g / tau_c);
      h[static_cast<std::size_t>(it - edges.begin())] += 1;
    };
    if (!o.quiet) fmt::print(stderr, "reproduce intervals: N = {}, e = {:g}, k = {:g}, {} launches\n", kN, e, k, launches);
    std::vector<CollisionRecord> current;
    const auto keep = [&](const std::vector<CollisionRecord>& recs) { current = recs; };
    run_collapse(spec, keep, {}, [&](const std::vector<ClosedState>& states) {
      const std::vector<CollisionRecord>& recs = current;
      const std::vector<Collision> seq = to_sequence(recs);
      SoftLaunch s;
      s.n = static_cast<double>(seq.size());
      for (double g : analysis::system_gaps(seq)) {
        gaps_total += 1;
        if (g <= 0) overlapping += 1;
        bin(gap_hist, g);
      }
      for (double g : analysis::pair_gaps(seq)) bin(pair_hist, g);
      const std::vector<analysis::CollapseEvent> evs = analysis::collapse_events(seq, kEventGap * tau_c, kEventMin);
      double previous_end = -1.0;
      std::vector<analysis::EventSpan> spans;
      std::vector<double> u_in, u_out;
      for (const auto& ev : evs) {
        s.events += 1;
        s.in_events += static_cast<double>(ev.collisions);
        s.particles += ev.particles;
        part_hist[static_cast<std::size_t>(std::min(ev.particles, kN))] += 1;
        // The event's approach speed (its first collision's), the speed its last collision
        // leaves, its duration, and the wait since the previous event, in tau_c.
        const CollisionRecord& first = recs[ev.first];
        const CollisionRecord& last = recs[ev.first + ev.collisions - 1];
        double end = first.t_end;
        for (std::size_t c = ev.first; c < ev.first + ev.collisions; ++c) end = std::max(end, recs[c].t_end);
        speed_bin(first.speed_in);
        if (first.speed_in > 0) rebound.push_back(last.speed_out / first.speed_in);
        const std::size_t last_index = ev.first + ev.collisions - 1;
        const auto at = std::lower_bound(states.begin(), states.end(), last_index,
                                         [](const ClosedState& c, std::size_t j) { return c.after < j; });
        if (first.speed_in > 0 && at != states.end() && at->after == last_index) {
          int lo = kN, hi = -1;  // 0-based particles: pair i (1-based) joins particles i - 1 and i
          for (std::size_t c = ev.first; c <= last_index; ++c) lo = std::min(lo, recs[c].i - 1), hi = std::max(hi, recs[c].i);
          const ChainState& cs = at->state;
          // The state holds absolute heights and velocities: a difference is read only where it
          // is at least 1e6 of their round-off (an event's speeds against the largest speed, its
          // gaps, of order u_a tau_c, against the largest height).
          double v_max = 0, z_max = 0;
          for (double v : cs.v) v_max = std::max(v_max, std::abs(v));
          for (double z : cs.z) z_max = std::max(z_max, std::abs(z));
          const double eps = std::numeric_limits<double>::epsilon();
          const bool speeds_resolved = first.speed_in * 0.01 >= 1e6 * eps * v_max;
          const bool gaps_resolved = first.speed_in * tau_c >= 1e6 * eps * z_max;
          double v_mean = 0;
          for (int j = lo; j <= hi; ++j) v_mean += cs.v[static_cast<std::size_t>(j)];
          v_mean /= hi - lo + 1;
          double e_int = 0;
          for (int j = lo; j <= hi; ++j) e_int += 0.5 * spec.params.m * std::pow(cs.v[static_cast<std::size_t>(j)] - v_mean, 2);
          if (speeds_resolved) internal_energy.push_back(e_int / (0.25 * spec.params.m * first.speed_in * first.speed_in));
          const double gaps = cs.z[static_cast<std::size_t>(hi)] - cs.z[static_cast<std::size_t>(lo)] - (hi - lo) * spec.params.d;
          if (gaps_resolved) spread.push_back(gaps / (first.speed_in * tau_c));
        }
        duration.push_back((end - first.t_begin) / tau_c);
        if (previous_end >= 0) {
          const double w = (first.t_begin - previous_end) / tau_c;
          wait.push_back(w);
          const double d = w > 0 ? std::floor(std::log10(w)) : 1.0;
          wait_hist[static_cast<std::size_t>(std::clamp(d, 1.0, static_cast<double>(kWaitDecades)) - 1.0)] += 1;
        }
        previous_end = end;
        spans.push_back({first.t_begin, end});
        u_in.push_back(first.speed_in), u_out.push_back(last.speed_out);
      }
      for (const analysis::Cascade& c : analysis::cascades(spans, kCascadeWait * tau_c)) {
        s.cascades += 1;
        for (std::size_t j = c.first + 1; j < c.first + c.events; ++j) {
          if (u_in[j] > 0 && u_out[j - 1] > 0) next_over_left.push_back(std::log10(u_in[j] / u_out[j - 1]));
          if (u_in[j] > 0 && u_in[j - 1] > 0) next_over_approach.push_back(std::log10(u_in[j] / u_in[j - 1]));
        }
      }
      L.push_back(s);
    });
    std::vector<double> n, events, frac, in_events, casc;
    double ev_sum = 0, p_sum = 0;
    for (const auto& s : L) {
      n.push_back(s.n), events.push_back(s.events), frac.push_back(s.n > 0 ? s.in_events / s.n : 0.0);
      in_events.push_back(s.in_events), casc.push_back(s.cascades);
      ev_sum += s.events, p_sum += s.particles;
    }
    // Collisions per event and events per cascade as ratios of sums over the launches.
    const auto [per, pe] = ratio_of_sums(in_events, events);
    const auto [epc, epc_err] = ratio_of_sums(events, casc);
    const auto [nm, ne] = mean_and_error(n);
    const auto [em, ee] = mean_and_error(events);
    const auto [fm, fe] = mean_and_error(frac);
    const auto [cm, ce] = mean_and_error(casc);
    ev_mean.push_back(em), ev_err.push_back(ee), per_mean.push_back(per), per_err.push_back(pe);
    casc_mean.push_back(cm), casc_err.push_back(ce), epc_mean.push_back(epc), epc_err_v.push_back(epc_err);
    double waits = 0;
    for (double h : wait_hist) waits += h;
    cascade_rows += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} |", power_of_ten_text(k), plus_minus(cm, ce, 1), plus_minus(epc, epc_err, 2),
                                median(next_over_left), median(next_over_approach));
    for (double& h : wait_hist) {
      h /= std::max(1.0, waits);
      cascade_rows += fmt::format(" {:.3f} |", h);
    }
    cascade_rows += "\n";
    md += fmt::format("| {} | {} | {} | {} | {:.1f} | {} | {:.3f} |\n", power_of_ten_text(k), plus_minus(nm, ne, 1), plus_minus(em, ee, 1),
                      plus_minus(per, pe, 2), ev_sum > 0 ? p_sum / ev_sum : 0.0, plus_minus(fm, fe, 3), gaps_total > 0 ? overlapping / gaps_total : 0.0);
    for (double& h : speed_hist) h /= std::max<double>(1.0, static_cast<double>(L.size()));
    speed_rows += fmt::format("| {} | {:.3g} | {:.3g} | {:.3g} | {:.1f} | {:.1f} |", power_of_ten_text(k), median(rebound), median(internal_energy),
                              median(spread), median(duration), median(wait));
    for (int d = kSpeedDecades - 1; d >= kSpeedDecades - kSpeedColumns; --d) speed_rows += fmt::format(" {:.1f} |", speed_hist[static_cast<std::size_t>(d)]);
    speed_rows += "\n";
    for (double& h : gap_hist) h /= std::max(1.0, gaps_total);
    out.json["per_k"].push_back({{"k", k}, {"tau_c", tau_c}, {"n_tot", nm}, {"n_tot_error", ne}, {"events", em}, {"events_error", ee},
                                 {"per_event", per}, {"per_event_error", pe}, {"fraction_in_events", fm}, {"gap_hist", gap_hist},
                                 {"pair_gap_hist", pair_hist}, {"particles_hist", part_hist}, {"overlapping", gaps_total > 0 ? overlapping / gaps_total : 0.0},
                                 {"events_by_speed_decade", speed_hist}, {"median_rebound_ratio", median(rebound)},
                                 {"median_duration_tau_c", median(duration)}, {"median_wait_tau_c", median(wait)},
                                 {"median_internal_energy", median(internal_energy)}, {"median_gaps_over_ua_tau_c", median(spread)},
                                 {"cascades", cm}, {"cascades_error", ce}, {"events_per_cascade", epc}, {"events_per_cascade_error", epc_err},
                                 {"wait_decades", wait_hist}});
  }
  out.json["edges"] = edges;
  md += fmt::format("\nEach collapse event by its approach speed u_a (the relative speed of its first collision, launch speed 1): "
                    "the median ratio u_r / u_a of the speed its last collision leaves to u_a; the cluster it leaves, read from the chain "
                    "when its last contact has ended (events during which another contact stays open elsewhere are left out): the "
                    "median kinetic energy of its particles about their centre of mass over the approach energy m u_a² / 4, and the "
                    "median sum of its gaps over u_a τ_c (each over the events where the chain's absolute velocities, or heights, "
                    "resolve 1 % of u_a, or u_a τ_c, to 1e6 times their round-off); its median duration and the median wait since the previous event (τ_c); "
                    "and the events per launch in each decade of u_a (column 1e-m: 1e-m ≤ u_a < 1e-(m-1)):\n\n| k | u_r / u_a | "
                    "internal energy / (m u_a² / 4) | gaps / (u_a τ_c) | duration | wait |");
  for (int c = 0; c < kSpeedColumns; ++c) md += fmt::format(" 1e{} |", -c - 1);  // the decade [1e-(c+1), 1e-c)
  md += "\n|---|---|---|---|---|---|";
  for (int c = 0; c < kSpeedColumns; ++c) md += "---|";
  md += "\n" + speed_rows;
  md += fmt::format("\nCascades: runs of events each beginning less than {:g} τ_c after the previous one ended. Per k: cascades per launch, "
                    "events per cascade, the medians of log10 u_a(n+1) / u_r(n) (the next event's approach speed against the speed the "
                    "previous one left) and of log10 u_a(n+1) / u_a(n) for successive events of a cascade, and the fraction of the "
                    "waits between successive events in each decade of wait / τ_c (column 1e1: 1e1 ≤ wait < 1e2, the least wait the "
                    "event rule allows; the last column holds the waits of 1e10 τ_c and more):\n\n| k | cascades | events per cascade | "
                    "u_a(n+1)/u_r(n) | u_a(n+1)/u_a(n) |",
                    kCascadeWait);
  for (int d = 1; d <= kWaitDecades; ++d) md += fmt::format(" 1e{} |", d);
  md += "\n|---|---|---|---|---|";
  for (int d = 0; d < kWaitDecades; ++d) md += "---|";
  md += "\n" + cascade_rows;
  if (ks.size() >= 2) {
    // A power of ln k, (ln k)^beta, has the local exponent beta / ln k: the events' exponent times
    // ln k at the middle of the interval is that beta, constant for such a law.
    md += "\nLocal exponents d ln / d ln k between successive k (errors as if independent), and the events' exponent times "
          "ln √(k1 k2): the β of (ln k)^β, constant if the events grow as a power of ln k:\n\n"
          "| k1 → k2 | events per launch | × ln √(k1 k2) | collisions per event | cascades per launch | × ln √(k1 k2) | events per cascade |\n"
          "|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i + 1 < ks.size(); ++i) {
      const double span = std::log(ks[i + 1] / ks[i]), mid = 0.5 * std::log(ks[i + 1] * ks[i]);
      const auto slope = [&](const std::vector<double>& m) { return std::log(m[i + 1] / m[i]) / span; };
      const auto slope_error = [&](const std::vector<double>& m, const std::vector<double>& er) {
        return std::hypot(er[i] / m[i], er[i + 1] / m[i + 1]) / span;
      };
      md += fmt::format("| {} → {} | {} | {} | {} | {} | {} | {} |\n", power_of_ten_text(ks[i]), power_of_ten_text(ks[i + 1]),
                        plus_minus(slope(ev_mean), slope_error(ev_mean, ev_err), 3),
                        plus_minus(slope(ev_mean) * mid, slope_error(ev_mean, ev_err) * mid, 2),
                        plus_minus(slope(per_mean), slope_error(per_mean, per_err), 3),
                        plus_minus(slope(casc_mean), slope_error(casc_mean, casc_err), 3),
                        plus_minus(slope(casc_mean) * mid, slope_error(casc_mean, casc_err) * mid, 2),
                        plus_minus(slope(epc_mean), slope_error(epc_mean, epc_err_v), 3));
    }
  }
  return out;
}

}  // namespace

FigureOutcome reproduce_collision_intervals(const ReproduceFlags& o, ReproductionLog&) {
  const int hard_launches = o.smoke() ? 20 : o.paper() ? 1000 : 200;
  const int soft_launches = o.smoke() ? 4 : o.paper() ? 200 : 40;
  const std::vector<double> ks = o.smoke() ? std::vector<double>{1e5, 1e6} : o.paper() ? std::vector<double>{1e6, 1e8, 1e10, 1e12, 1e14, 1e16, 1e18, 1e20}
                                                                                         : std::vector<double>{1e6, 1e8, 1e10};
  nlohmann::json plot = {{"N", kN}, {"event_gap", kEventGap}, {"hard", nlohmann::json::array()}, {"soft", nlohmann::json::array()}};
  std::string md = fmt::format(
      "Command: `{}`. Free-space launches of Sec. III.D at N = {} (a = v0 = 1, dv0 = 0.1). "
      "Hard spheres: the engine's collapse watch (1000 collisions within 1e-9) marks the collapse; t* is the time of the last "
      "collision. Soft spheres: exact engine, stop rule `ends`; a collapse event is a run of at least {} collisions whose successive "
      "gaps (next contact begins − last one ended) are below {:g} τ_c. Figure: `intervals.png` (and .pdf).\n",
      reproduce_command_line(o), kN, kEventMin, kEventGap);
  for (double e : {0.3, 0.5}) {
    Section h = hard_sequences(e, hard_launches, o);
    Section s = soft_sequences(e, ks, soft_launches, o);
    plot["hard"].push_back(h.json);
    plot["soft"].push_back(s.json);
    md += h.markdown + s.markdown;
  }
  return {FigureStatus::Done, md, draw_figure(o, "intervals", plot, "intervals.py"), -1.0, "", {}};
}

}  // namespace granchain
