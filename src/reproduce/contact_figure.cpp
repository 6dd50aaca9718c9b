// `granchain reproduce --figure contacts` (group `columns`): how long neighbours stay in contact,
// against height in the column, per N. The paper's Summary expects that at large N "the load on the
// particles near the floor becomes so large that the contacts among them cannot be resolved into
// binary collisions but may remain as long-lived contacts in the range of k investigated". A binary
// collision lasts tau_c (Eq. tauc); the figure measures, per pair, the fraction of the window in
// contact and the mean duration in units of tau_c, and per layer the share of contact time spent in
// contacts longer than 2 tau_c (analysis/contact_layers.hpp), at fixed c = N (1 - e) across the
// critical region and on the power-law side, against k.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>

#include "analysis/blocking.hpp"
#include "analysis/contact_layers.hpp"
#include "analysis/estimate_format.hpp"
#include "config/value_list.hpp"
#include "reproduce/figures.hpp"
#include "store/results_store.hpp"

namespace granchain {

namespace {

constexpr int kReplicas = 2;  // the error of a layer's value: half the difference of the two
constexpr int kLayers = 10;   // tenths of the column, bottom first

// The columns' choices of e: c = N (1 - e) = 2 (uncollapsing, below the paper's 2.6), c = 5 (past
// e_c2, the paper's 3.0) and e = 0.3 (the power-law side of Fig. powerexpo).
struct EChoice {
  const char* label;
  double c;  // 0: the fixed e below
  double e;
};
const std::vector<EChoice> kChoices = {{"N(1 − e) = 2", 2.0, 0.0}, {"N(1 − e) = 5", 5.0, 0.0}, {"e = 0.3", 0.0, 0.3}};

std::vector<int> contact_ns(const ReproduceFlags& o) {
  if (o.smoke()) return {10, 25};
  if (o.large()) return {25, 50, 100, 150, 300, 1000};
  if (o.paper()) return {25, 50, 100, 150};
  return {25, 50, 100};
}
std::string contact_k(const ReproduceFlags& o) { return o.paper() ? "1e6,1e8,1e10" : o.smoke() ? "1e4" : "1e4,1e6"; }
std::string contact_T(const ReproduceFlags& o) { return o.paper() ? "200" : o.smoke() ? "5" : "50"; }

std::string e_of(const EChoice& c, int N) {
  return c.c > 0 ? e_list_at_n_one_minus_e(N, {c.c}) : fmt::format("{:g}", c.e);
}

// A value over the replicas: their mean and the standard error of the mean (two replicas:
// |a - b| / 2; mean_and_error), the error NaN from a single replica (a point whose second replica
// is not stored yet).
struct ReplicaValue {
  double value = 0, error = 0;
};
ReplicaValue over_replicas(const std::vector<double>& x) {
  const auto [value, error] = mean_and_error(x);
  return {value, error};
}

// "0.0130 ± 0.0021" (the error to two significant digits), "0.013 (one run)" without an error.
std::string value_text(const ReplicaValue& v) {
  if (!std::isfinite(v.value)) return "-";  // (a long-contact share of runs stored before it was kept)
  if (std::isfinite(v.error) && v.error > 0) return format_with_error(v.value, v.error);
  if (std::isfinite(v.error)) return fmt::format("{:.4g} ± 0", v.value);  // the replicas agree exactly
  return fmt::format("{:.4g} (one run)", v.value);
}

}  // namespace

std::vector<GridBlock> contacts_grid(const ReproduceFlags& o) {
  std::vector<GridBlock> blocks;
  for (int N : contact_ns(o)) {
    std::string es;
    for (const EChoice& c : kChoices) es += (es.empty() ? "" : ",") + e_of(c, N);
    GridBlock b{std::to_string(N), es, contact_k(o), contact_T(o), "1", kReplicas};
    b.transient = settling_transient(N);
    blocks.push_back(b);
  }
  return blocks;
}

FigureOutcome reproduce_contacts(const ReproduceFlags& o, ReproductionLog& log) {
  const std::vector<GridBlock> blocks = contacts_grid(o);
  const std::vector<SweepPoint> points = grid_points(blocks);
  const std::vector<std::string> failures = run_missing_points(points, o, o.figure, log);
  ResultsStore store(o.db, ResultsStore::Access::ReadOnly);  // (run_missing_points made it, unless --stored-only)

  // Each (N, e, k): the stored replicas' results with contact durations.
  std::map<std::tuple<int, double, double>, std::vector<RunResult>> cells;
  double cpu = 0;
  int stationary = 0, stored = 0;
  for (const SweepPoint& p : points) {
    std::optional<ResultsStore::ReadBack> r = store.read_back_run(p.spec);
    if (!r) continue;
    ++stored;
    cpu += r->result.cpu_seconds > 0 ? r->result.cpu_seconds : r->result.wall_seconds;
    stationary += r->result.stationary() ? 1 : 0;
    if (r->result.contacts.size() >= 2) cells[{p.spec.params.N, p.spec.params.e, p.spec.params.k}].push_back(std::move(r->result));
  }
  if (o.stored_only && stored == 0) throw NothingStored(fmt::format("none of the {} runs of contacts is in {}", points.size(), o.db));
  if (stored < static_cast<int>(points.size()))
    log.partial.push_back(fmt::format("contacts: {} of {} runs", stored, points.size()));

  nlohmann::json plot = {{"choices", nlohmann::json::array()},
                         {"long_contact", analysis::kLongContact},
                         {"log2_min", ContactDurations::kLog2Min},
                         {"bins_per_octave", ContactDurations::kBinsPerOctave}};
  std::string md = fmt::format(
      "Command: `{}`. Contact durations of the driven column (k_B T0 = 1, exact engine, T = {}, transient T/10, {} replicas per "
      "point), N = {}, at c = N(1 − e) = 2 and 5 and at e = 0.3, k = {}. Per pair (i, i+1): the fraction of the window in "
      "contact and the mean contact duration in units of τ_c (a binary collision lasts τ_c, Eq. tauc); per tenth of the column: "
      "the share of its time in contact spent in contacts longer than {:g} τ_c (three or more particles held together; contacts "
      "still open at the window's end included). Values are the mean of the replicas, errors half "
      "their difference (\"one run\" where the second is not stored yet). {} of {} runs stored, {} stationary by the run's own verdict; {:.2f} CPU-hours. Figure: `contacts.png` "
      "(and .pdf): per choice of e, at the smallest k (where contacts last longest), (top) fraction in contact and (second row) "
      "mean duration against the pair's "
      "height i/N, one curve per N; (third row) the long-contact share of the bottom tenth against k; (bottom) the distribution of "
      "the bottom tenth's contact durations at the smallest k (contacts per octave of duration, normalised to 1).\n",
      reproduce_command_line(o), contact_T(o), kReplicas, blocks.front().N + " … " + blocks.back().N, contact_k(o),
      analysis::kLongContact, stored, points.size(), stationary, cpu / 3600.0);

  for (const EChoice& choice : kChoices) {
    nlohmann::json jc = {{"label", choice.label}, {"columns", nlohmann::json::array()}};
    md += fmt::format("\n### {}\n\n| N | e | k | bottom tenth: in contact | mean / τ_c | longest / τ_c | share > {:g} τ_c | "
                      "whole column: in contact | mean / τ_c | longest / τ_c | share > {:g} τ_c | tenth most in contact |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                      choice.label, analysis::kLongContact, analysis::kLongContact);
    for (int N : contact_ns(o)) {
      // (the values as the grid parsed them, so that they find its points)
      const double e = parse_value_list(e_of(choice, N), "--e").front();
      nlohmann::json col = {{"N", N}, {"e", e}, {"k", nlohmann::json::array()}};
      for (const double k : parse_value_list(contact_k(o), "--k")) {
        const auto found = cells.find({N, e, k});
        if (found == cells.end()) continue;
        const std::vector<RunResult>& runs = found->second;
        // Per layer and per replica, then over the replicas.
        std::vector<std::vector<analysis::ContactLayer>> tenths;
        std::vector<analysis::ContactLayer> whole;
        for (const RunResult& r : runs) {
          tenths.push_back(analysis::contact_layers(r.contacts, kLayers));
          whole.push_back(analysis::contact_layer(r.contacts, 1, static_cast<int>(r.contacts.size()) - 1));
        }
        const auto over = [&](const std::vector<analysis::ContactLayer>& ls, auto field) {
          std::vector<double> x;
          for (const auto& l : ls) x.push_back(field(l));
          return over_replicas(x);
        };
        const auto frac = [](const analysis::ContactLayer& l) { return l.contact_fraction; };
        const auto mean = [](const analysis::ContactLayer& l) { return l.mean_duration; };
        const auto longest = [](const analysis::ContactLayer& l) { return l.longest; };
        const auto share = [](const analysis::ContactLayer& l) { return l.long_share; };
        std::vector<analysis::ContactLayer> bottom;
        for (const auto& t : tenths) bottom.push_back(t.front());
        int top_layer = 0;
        double top_fraction = -1;
        for (int l = 0; l < static_cast<int>(tenths.front().size()); ++l) {
          std::vector<analysis::ContactLayer> ls;
          for (const auto& t : tenths) ls.push_back(t[static_cast<std::size_t>(l)]);
          const double f = over(ls, frac).value;
          if (f > top_fraction) top_fraction = f, top_layer = l;
        }
        md += fmt::format("| {} | {:.6g} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} ({:.3f}) |\n", N, e, power_of_ten_text(k),
                          value_text(over(bottom, frac)), value_text(over(bottom, mean)), value_text(over(bottom, longest)),
                          value_text(over(bottom, share)), value_text(over(whole, frac)), value_text(over(whole, mean)),
                          value_text(over(whole, longest)), value_text(over(whole, share)), top_layer + 1, top_fraction);
        // Per pair, over the replicas, for the profiles.
        nlohmann::json height = nlohmann::json::array(), fraction = nlohmann::json::array(), duration = nlohmann::json::array();
        const std::size_t pairs = runs.front().contacts.size();
        for (std::size_t i = 1; i < pairs; ++i) {
          double f = 0, d = 0;
          for (const RunResult& r : runs) f += r.contacts[i].contact_fraction, d += r.contacts[i].mean;
          height.push_back(static_cast<double>(i) / N);
          fraction.push_back(f / static_cast<double>(runs.size()));
          duration.push_back(d / static_cast<double>(runs.size()));
        }
        // The bottom tenth's durations pooled over its pairs and the replicas: contacts per bin of
        // log2(duration / tau_c) from bin `first_bin` on (the contacts that ended in the window).
        std::map<int, std::uint64_t> pooled;
        for (const RunResult& r : runs)
          for (int i = tenths.front().front().first_pair; i <= tenths.front().front().last_pair; ++i) {
            const PairContacts& p = r.contacts[static_cast<std::size_t>(i)];
            for (std::size_t j = 0; j < p.histogram.size(); ++j)
              if (p.histogram[j] > 0) pooled[p.first_bin + static_cast<int>(j)] += p.histogram[j];
          }
        nlohmann::json counts = nlohmann::json::array();
        const int first_bin = pooled.empty() ? 0 : pooled.begin()->first;
        if (!pooled.empty())
          for (int b = first_bin; b <= pooled.rbegin()->first; ++b) counts.push_back(pooled.count(b) ? pooled[b] : 0);
        const ReplicaValue bs = over(bottom, share);
        col["k"].push_back({{"k", k}, {"height", height}, {"fraction", fraction}, {"mean", duration},
                            {"bottom_long_share", bs.value}, {"bottom_long_share_err", bs.error},
                            {"bottom_histogram", {{"first_bin", first_bin}, {"counts", counts}}}});
      }
      if (!col["k"].empty()) jc["columns"].push_back(col);
    }
    plot["choices"].push_back(jc);
  }
  md += "\nTenths are counted from the floor (1: pairs 1 … N/10). The contact fraction of a layer is the mean over its pairs; "
        "its mean duration weights each pair by its number of contacts.\n";
  FigureOutcome out;
  out.drawn = draw_figure(o, "contacts", plot, "contacts.py");
  out.status = failures.empty() ? FigureStatus::Done : FigureStatus::PointsFailed;
  out.failed_points = failures;
  out.run_seconds = cpu;
  out.markdown = md;
  return out;
}

}  // namespace granchain
