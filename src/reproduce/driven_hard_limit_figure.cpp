// `granchain reproduce --figure limit-hard` (group `beyond`): the driven column's hard-sphere limit.
// Hard spheres (k = infinity at fixed e) on the thermal floor either run through the window with a
// finite n_coll, or meet an inelastic collapse; the threshold e_h between the two, from the column's
// initial state and from the soft column's stationary state (--start-k), and the exact engine's
// n_coll(k) at k = 1e10 ... 1e30 beside the hard-sphere value it must converge to above e_h.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <nlohmann/json.hpp>

#include "config/value_list.hpp"
#include "reproduce/figures.hpp"
#include "store/results_store.hpp"

namespace granchain {

namespace {

// A soft series: the exact engine at N, e over a k list, measuring time T.
struct SoftSeries {
  int N;
  double e;
  std::string k, T;
};
// A threshold scan: the hard engine at N over an e list, replicas per point, from the initial state
// and (start_k not empty) from the soft column at k = start_k.
struct HardScan {
  int N;
  std::string e;
  bool stationary_too;
};
struct Plan {
  std::vector<SoftSeries> soft;
  std::vector<HardScan> hard;
  std::string hard_T, start_k;
  int replicas;
};

Plan plan(const ReproduceFlags& o) {
  if (o.smoke()) return {{{10, 0.5, "1e6:1e10:x100", "20"}, {10, 0.6, "1e6:1e10:x100", "20"}}, {{10, "0.5,0.6", true}}, "20", "1e8", 2};
  if (!o.paper())
    return {{{10, 0.5, "1e10:1e22:x100", "200"},
             {10, 0.55, "1e10:1e22:x100", "200"},
             {25, 0.76, "1e10:1e22:x100", "200"},
             {25, 0.8, "1e10:1e22:x100", "200"},
             {25, 0.85, "1e10:1e22:x100", "200"}},
            {{10, "0.5,0.51,0.52,0.53,0.54,0.55", true}, {25, "0.76,0.764,0.768,0.772,0.776,0.78", true}, {25, "0.8,0.85", false}},
            "200",
            "1e12",
            4};
  Plan p{{}, {}, "1000", "1e14", 4};
  for (double e : {0.5, 0.55}) p.soft.push_back({10, e, "1e10:1e30:x100", "1000"});
  for (double e : {0.76, 0.78, 0.8, 0.82, 0.85, 0.88}) p.soft.push_back({25, e, "1e10:1e30:x10", "1000"});
  for (double e : {0.88, 0.9}) p.soft.push_back({50, e, "1e10:1e30:x100", "200"});
  p.soft.push_back({100, 0.94, "1e10:1e26:x100", "100"});  // below e_h: n_coll and the cost grow without bound
  p.soft.push_back({100, 0.96, "1e10:1e30:x100", "100"});
  p.hard = {{10, "0.5,0.51,0.52,0.53,0.54,0.55", true},
            {25, "0.76,0.764,0.768,0.772,0.776,0.78", true},
            {25, "0.8,0.82,0.85,0.88", false},
            {50, "0.88", false},
            {50, "0.89,0.892,0.894,0.896,0.898,0.9", true},
            {100, "0.94", false},
            {100, "0.95,0.951,0.952,0.953,0.954,0.955", true},
            {100, "0.96", false}};
  return p;
}

std::string e_text(double e) { return fmt::format("{:g}", e); }

// What the hard replicas of one (N, e, start) did: the runs' n_coll and the collapses' instants.
struct Outcome {
  std::vector<double> n_coll;
  std::vector<double> collapse_t;  // from the start (initial state), or from the hand-over at the transient's end (soft start)
  int missing = 0;
  double mean() const {
    double s = 0;
    for (double x : n_coll) s += x;
    return n_coll.empty() ? NAN : s / static_cast<double>(n_coll.size());
  }
  // The replicas' standard error (of the mean); NaN for fewer than two.
  double error() const {
    if (n_coll.size() < 2) return NAN;
    const double m = mean();
    double v = 0;
    for (double x : n_coll) v += (x - m) * (x - m);
    return std::sqrt(v / static_cast<double>(n_coll.size() - 1) / static_cast<double>(n_coll.size()));
  }
};

std::string waits_text(std::vector<double> t) {
  if (t.empty()) return "";
  std::sort(t.begin(), t.end());
  return t.size() == 1 ? fmt::format("{:.3g}", t.front()) : fmt::format("{:.3g} – {:.3g}", t.front(), t.back());
}

}  // namespace

std::vector<GridBlock> hard_limit_grid(const ReproduceFlags& o) {
  const Plan p = plan(o);
  std::vector<GridBlock> blocks;
  for (const SoftSeries& s : p.soft) blocks.push_back({std::to_string(s.N), e_text(s.e), s.k, s.T});
  for (const HardScan& h : p.hard) {
    GridBlock b{std::to_string(h.N), h.e, "", p.hard_T, "1", p.replicas};
    b.engine = "hard";
    blocks.push_back(b);
    if (h.stationary_too) {
      b.start_k = p.start_k;
      blocks.push_back(b);
    }
  }
  return blocks;
}

FigureOutcome reproduce_hard_limit(const ReproduceFlags& o, ReproductionLog& log) {
  const Plan p = plan(o);
  const std::vector<SweepPoint> points = grid_points(hard_limit_grid(o));
  const std::vector<std::string> failed = run_missing_points(points, o, "limit-hard", log);
  ResultsStore store(o.db, ResultsStore::Access::ReadOnly);
  const auto runs = store.point_summaries();
  const auto collapses = store.collapsed_points();
  const double start_k = parse_value_list(p.start_k, "--start-k").front();

  // The hard replicas by (N, e, soft start) and the soft values by (N, e) and k.
  std::map<std::tuple<int, double, bool>, Outcome> hard;
  std::map<std::pair<int, double>, std::map<double, std::pair<double, double>>> soft;
  int stored = 0;
  for (const SweepPoint& pt : points) {
    const RunSpec& s = pt.spec;
    const auto run = runs.find(pt.key);
    if (run != runs.end()) ++stored;
    if (s.engine.kind != EngineKind::Hard) {
      if (run != runs.end()) soft[{s.params.N, s.params.e}][s.params.k] = {run->second.n_coll, run->second.n_coll_err};
      continue;
    }
    Outcome& out = hard[{s.params.N, s.params.e, s.engine.start_k > 0}];
    if (run != runs.end()) out.n_coll.push_back(run->second.n_coll);
    else if (const auto c = collapses.find(pt.key); c != collapses.end()) {
      out.collapse_t.push_back(s.engine.start_k > 0 ? c->second.t - s.transient : c->second.t);
      ++stored;
    } else {
      ++out.missing;
    }
  }
  if (o.stored_only && stored == 0) throw NothingStored(fmt::format("none of the runs of limit-hard is in {}", o.db));

  std::string md = fmt::format(
      "Command: `{}`. The driven column (k_B T0 = 1) with hard spheres (k = ∞, `--engine hard`, {} replicas per point, T = {}, "
      "transient T/10), from the column's initial state and from the soft column's state at the end of the transient, run by "
      "the exact engine at k = {} (`--start-k`); a replica either runs through T (stored as a run) or meets an inelastic "
      "collapse (1000 collisions within 1e-9, stored as a collapse with its instant, no n_coll). Beside them the exact "
      "engine's n_coll over the k of each series below, one run per point. Figure: `limit-hard.png` (and .pdf).\n\n"
      "### Where hard spheres collapse\n\n"
      "n_coll is the replicas' mean with its standard error; the difference is that of the two starts in combined errors.\n\n"
      "| N | e | N(1 − e) | initial state: run / collapsed | collapse at t | n_coll | soft start: run / collapsed "
      "| collapse at t − transient | n_coll | difference / σ |\n|---|---|---|---|---|---|---|---|---|---|\n",
      reproduce_command_line(o), p.replicas, p.hard_T, power_of_ten_text(start_k));
  nlohmann::json thresholds = nlohmann::json::array();
  std::map<std::pair<int, bool>, std::pair<double, double>> bounds;  // (N, soft start) -> (highest e all collapse, lowest e none)
  for (const auto& [key, out] : hard) {
    const auto [N, e, from_soft] = key;
    const double c = N * (1.0 - e);
    thresholds.push_back({{"N", N}, {"e", e}, {"c", c}, {"soft_start", from_soft}, {"ran", out.n_coll.size()},
                          {"collapsed", out.collapse_t.size()}, {"missing", out.missing}, {"waits", out.collapse_t},
                          {"n_coll", std::isfinite(out.mean()) ? nlohmann::json(out.mean()) : nlohmann::json(nullptr)},
                          {"n_coll_error", std::isfinite(out.error()) ? nlohmann::json(out.error()) : nlohmann::json(nullptr)}});
    auto& [all_collapse, none_collapse] = bounds.try_emplace({N, from_soft}, -INFINITY, INFINITY).first->second;
    if (out.missing == 0 && out.n_coll.empty()) all_collapse = std::max(all_collapse, e);
    if (out.missing == 0 && out.collapse_t.empty()) none_collapse = std::min(none_collapse, e);
    if (from_soft) continue;
    const auto cell = [](const Outcome* h) -> std::string {
      if (!h) return "| | | ";
      return fmt::format("| {} / {}{} | {} | {} ", h->n_coll.size(), h->collapse_t.size(), h->missing ? fmt::format(" ({} not run)", h->missing) : "",
                         waits_text(h->collapse_t), h->n_coll.empty()               ? ""
                         : h->n_coll.size() == 1 ? fmt::format("{:.1f} (one run)", h->mean())
                                                 : plus_minus(h->mean(), h->error(), 1));
    };
    const auto other = hard.find({N, e, true});
    const Outcome* s = other != hard.end() ? &other->second : nullptr;
    std::string diff;
    if (s && s->n_coll.size() >= 2 && out.n_coll.size() >= 2)
      diff = fmt::format("{:+.1f}", (s->mean() - out.mean()) / std::hypot(s->error(), out.error()));
    md += fmt::format("| {} | {:g} | {:.2f} {}{}| {} |\n", N, e, c, cell(&out), cell(s), diff);
  }
  md += "\n";
  for (const auto& [key, b] : bounds) {
    const auto [N, from_soft] = key;
    md += fmt::format("- N = {}, {}: every replica collapses at e ≤ {}, none at e ≥ {}: N(1 − e_h) between {} and {}.\n", N,
                      from_soft ? fmt::format("soft start (k = {})", power_of_ten_text(start_k)) : "initial state",
                      std::isfinite(b.first) ? fmt::format("{:g}", b.first) : "—", std::isfinite(b.second) ? fmt::format("{:g}", b.second) : "—",
                      std::isfinite(b.second) ? fmt::format("{:.2f}", N * (1 - b.second)) : "—",
                      std::isfinite(b.first) ? fmt::format("{:.2f}", N * (1 - b.first)) : "—");
  }

  // The soft series against the hard value: settled from the first k after which every value lies
  // within 3 combined errors of it; below e_h, the growth per step of k.
  md += "\n### The soft column against the hard-sphere value\n";
  nlohmann::json series = nlohmann::json::array();
  for (const SoftSeries& ss : p.soft) {
    const auto it = soft.find({ss.N, ss.e});
    const auto h = hard.find({ss.N, ss.e, false});
    const Outcome* ho = h != hard.end() ? &h->second : nullptr;
    const bool hard_runs = ho && ho->n_coll.size() >= 2 && ho->collapse_t.empty() && ho->missing == 0;
    const bool hard_collapses = ho && !ho->collapse_t.empty();
    md += fmt::format("\n#### N = {}, e = {:g} (T = {}): hard spheres {}\n\n", ss.N, ss.e, ss.T,
                      hard_runs ? fmt::format("run, n_coll = {}", plus_minus(ho->mean(), ho->error(), 1))
                                : hard_collapses ? "collapse" : "not known (no replica stored)");
    if (it == soft.end()) {
      md += "No soft run stored.\n";
      log.partial.push_back(fmt::format("limit-hard (N = {}, e = {:g}): no soft run", ss.N, ss.e));
      continue;
    }
    std::vector<double> k, y, err;
    for (const auto& [kk, v] : it->second) k.push_back(kk), y.push_back(v.first), err.push_back(v.second);
    const std::size_t expected = parse_value_list(ss.k, "--k").size();
    if (k.size() < expected) log.partial.push_back(fmt::format("limit-hard (N = {}, e = {:g}): {} of {} soft runs", ss.N, ss.e, k.size(), expected));
    md += hard_runs ? "| k | n_coll | (n − n_hard) / σ |\n|---|---|---|\n" : "| k | n_coll | rise from the previous k |\n|---|---|---|\n";
    std::size_t settled = k.size();
    for (std::size_t i = k.size(); i-- > 0;) {
      if (!hard_runs || !std::isfinite(err[i]) || !(std::abs(y[i] - ho->mean()) <= 3 * std::hypot(err[i], ho->error()))) break;
      settled = i;
    }
    for (std::size_t i = 0; i < k.size(); ++i)
      md += fmt::format("| {} | {} | {} |\n", power_of_ten_text(k[i]), plus_minus(y[i], err[i], 1),
                        hard_runs ? fmt::format("{:+.1f}", (y[i] - ho->mean()) / std::hypot(err[i], ho->error()))
                                  : i ? fmt::format("{:.1f}", y[i] - y[i - 1]) : "");
    if (hard_runs)
      md += settled < k.size() ? fmt::format("\nSettled on the hard-sphere value from k = {} on (every value within 3 σ).\n", power_of_ten_text(k[settled]))
                               : "\nNot settled on the hard-sphere value within this k range.\n";
    series.push_back({{"N", ss.N}, {"e", ss.e}, {"T", ss.T}, {"k", k}, {"y", y}, {"error", err},
                      {"hard", hard_runs ? nlohmann::json{{"value", ho->mean()}, {"error", ho->error()}} : nlohmann::json(nullptr)},
                      {"hard_collapses", hard_collapses}});
  }
  const nlohmann::json plot = {{"title", "the driven column's hard-sphere limit"}, {"series", series}, {"thresholds", thresholds},
                               {"start_k", start_k}, {"replicas", p.replicas}};
  FigureOutcome out{failed.empty() ? FigureStatus::Done : FigureStatus::PointsFailed, md, draw_figure(o, "limit-hard", plot, "hard_limit.py"),
                    -1.0, "", failed};
  for (const std::string& f : failed) out.markdown += "\nFailed point (left out): " + f + "\n";
  return out;
}

}  // namespace granchain
