#include "cli/subcommand.hpp"
#include "sweep/sweep_progress.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <chrono>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <nlohmann/json.hpp>
#include <thread>

#include "config/input_error.hpp"
#include "provenance.hpp"
#include "version.hpp"
#include "cli/interrupt_message.hpp"
#include "store/output_file.hpp"
#include "config/collapse_options.hpp"
#include "config/value_list.hpp"
#include "engines/engine.hpp"
#include "simulation/collapse_run.hpp"
#include "store/collapse_json.hpp"
#include "store/results_store.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain {

namespace {

struct CollapseFlags {
  std::map<std::string, std::string> values;  // parameter name -> text from the command line
  std::map<std::string, CLI::Option*> options;
  std::string events_path, json_path, db_path = "granchain.db";
  CLI::Option* json_option = nullptr;
  bool no_db = false, quiet = false, progress_lines = false;
};

int execute_collapse(const std::shared_ptr<CollapseFlags>& impl_);

}  // namespace

Subcommand add_collapse_command(CLI::App& app) {
  auto impl_ = std::make_shared<CollapseFlags>();
  CLI::App* sub_;
  sub_ = app.add_subcommand("collapse", "Count the collisions n_tot of an inelastic collapse in free space (or on a wall), "
                                        "averaged over random launches.");
  auto& o = *impl_;
  for (const Parameter& p : collapse_parameters())
    o.options[p.name] = sub_->add_option("--" + p.name, o.values[p.name], p.help())->type_name(p.type_name());
  sub_->add_option("--events", o.events_path, "write every collision (e, k, realisation, index, contact begin and end "
                                              "times, pair, speeds in and out) as CSV to FILE")
      ->type_name("FILE");
  o.json_option = sub_->add_option("--json", o.json_path, "write the results as JSON to FILE, or to standard output if no FILE")
                      ->expected(0, 1)
                      ->type_name("[FILE]");
  sub_->add_option("--db", o.db_path, "results store (SQLite), table collapse_runs; default granchain.db")->type_name("PATH");
  sub_->add_flag("--no-db", o.no_db, "do not store the results");
  sub_->add_flag("--quiet,-q", o.quiet, "print nothing but errors (and JSON to standard output if asked)");
  sub_->add_flag("--progress", o.progress_lines,
                 "print progress (launches done, elapsed time, ETA, collisions/s) on standard error even with --quiet or off a terminal");
  sub_->footer(
      "Launch (free space, Sec. III.D): x_i = (i - (N+1)/2)(d + a), v_i = -v0 sgn(x_i) + dv0 xi_i, xi_i uniform\n"
      "in [-1, 1), no gravity. Wall: particle 1 a above the wall, gaps a, v_i = -v0 + dv0 xi_i; the wall\n"
      "returns particle 1 with e times its speed, like its mirror image (e_c(2N) = e_c^wall(N), Eq. symmetry).\n"
      "n_tot counts every collision (a contact that ends; a wall hit) until the stop rule holds. The rules\n"
      "are checked whenever no contact is open:\n"
      "  ends   (the paper's): v_N - v_1 > 0. Inner pairs may still approach; their later collisions\n"
      "         are not counted.\n"
      "  strict: v_{i+1} >= v_i for every neighbouring pair (and v_1 >= 0 on a wall): no pair approaches,\n"
      "         so no collision can follow; n_tot is then every collision of the launch. A launch\n"
      "         also ends when nothing happens up to t = 1e7 (pairs approaching by round-off only).\n"
      "Hard spheres (k = infinity) that collapse are counted as collapsed and left out of the mean.\n"
      "For each e with several k, the slope of n_tot against log10 k between successive k is computed\n"
      "from the per-launch differences (the same launches at every k), and alpha = d ln n_tot / d ln k\n"
      "from the two means (for n_tot ~ k^alpha); for N = 3 below e_c(3) the slope is\n"
      "shown beside Eq. (ntot-log) and beside -ln 10 / ln q, the slope of all collisions (see docs/collapse.md).\n"
      "With a store (--db, without --events) a count is carried over sittings: its launches are kept in the\n"
      "store's table collapse_launches as they finish, so a count stopped anywhere (Ctrl-C, a batch job's walltime)\n"
      "continues when the same command runs again, and gives the same numbers bit for bit; a count stored\n"
      "whole is read back, not counted again.\n" +
      exit_codes_help("2 bad input (nothing written), 3 unphysical (no count stored or written; the launches counted "
                      "before it stay in the store), 4 store failed"));
  return {sub_, [impl_] { return execute_collapse(impl_); }};
}

namespace {

std::string num(double x, const char* f = "{:.4f}") { return std::isfinite(x) ? fmt::format(fmt::runtime(f), x) : "-"; }

}  // namespace

namespace {

int execute_collapse(const std::shared_ptr<CollapseFlags>& impl_) {
  auto& o = *impl_;
  const bool json_requested = o.json_option->count() > 0;
  const bool json_stdout = json_requested && (o.json_path.empty() || is_standard_output(o.json_path));
  CollapseOptions opts;
  try {
    std::map<std::string, RawValue> raw;
    for (const auto& [name, option] : o.options)
      if (option->count() > 0) raw[name] = RawValue{o.values[name]};
    opts = resolve_collapse_options(raw);
    check_outputs({{"--db", o.no_db ? "" : o.db_path}, {"--events", o.events_path},
                   {"--json", json_requested && !json_stdout ? o.json_path : ""}}, {});
    if (!o.no_db) {
      check_storable(opts.base);
      ResultsStore::preflight(o.db_path);
    }
  } catch (const InputError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  const CollapseSpec& base = opts.base;
  const std::vector<double>& es = opts.es;
  const std::vector<double>& ks = opts.ks;
  const bool hard = engine_info(base.engine.kind).hard_spheres;
  const int N = base.params.N;
  set_parallelism(base.threads, 1);

  // The event file is written to a temporary name and renamed only when everything succeeded; a
  // target that is not a regular file (a device, a FIFO) is written directly.
  std::error_code fs_error;
  const bool events_direct = !o.events_path.empty() && std::filesystem::exists(o.events_path, fs_error) &&
                             !std::filesystem::is_regular_file(o.events_path, fs_error);
  const std::string events_tmp = o.events_path.empty() || events_direct ? "" : fmt::format("{}.tmp-{}", o.events_path, getpid());
  std::ofstream events;
  if (!o.events_path.empty()) {
    events.open(events_direct ? o.events_path : events_tmp);
    events << "e,k,realization,collision,t_begin,t_end,i,j,speed_in,speed_out\n";
  }
  // With a store (and no event file, which needs every launch run now) each count is carried over
  // sittings: its launches are kept in the store as they finish, a count stored whole is read
  // back, and a rerun of the same command continues where the last one stopped. The store is read
  // read-only until the first launch is kept or the first count stored (`writer`).
  const bool carry = !o.no_db && o.events_path.empty();
  std::shared_ptr<ResultsStore> writer;
  std::optional<ResultsStore> reader;
  try {
    if (carry && ResultsStore::holds_a_store(o.db_path)) reader.emplace(o.db_path, ResultsStore::Access::ReadOnly);
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitStoreFailed;
  }
  announce_on_interrupt(carry ? fmt::format("the counts did not finish; the launches that finished are kept in {} (table "
                                            "collapse_launches; those under way are lost) and the same command continues "
                                            "from them; nothing else was written", o.db_path)
                              : "the counts did not finish; nothing was stored or written",
                        events_tmp);
  auto remove_tmp = [&] {
    if (!events_tmp.empty()) std::filesystem::remove(events_tmp);
  };

  if (!o.quiet && !json_stdout) {
    fmt::print("N = {}, setup {}, engine {}, stop rule {}, {} launches per point, a = {}, v0 = {}, dv0 = {}\n", N,
               setup_name(base.setup), engine_name(base.engine.kind), rule_name(base.rule), base.realizations, base.launch.a,
               base.launch.v0, base.launch.dv0);
    fmt::print("{:>8} {:>10} {:>12} {:>9} {:>7} {:>7} {:>10} {:>8}\n", "e", "k", "n_tot", "+-", "min", "max", "collapsed",
               "seconds");
    std::fflush(stdout);
  }
  std::vector<CollapseResult> results;
  std::vector<std::optional<nlohmann::json>> read_back_json;  // per count: its stored JSON, if read back
  std::vector<KSlope> slopes;
  // Progress over all launches of all points: a line rewritten on a terminal (unless --quiet), or
  // plain lines every 10 s with --progress (a batch job's log).
  const bool tty = isatty(STDERR_FILENO) != 0;
  const bool show_progress = o.progress_lines || (tty && !o.quiet && !json_stdout);
  const SweepProgressPrinter printer(tty, "collapse", "launches");
  const auto t_start = std::chrono::steady_clock::now();
  auto t_last = t_start;
  // The point of list position (e, k) as counted: the spec, and what the store already holds of it.
  const auto point_spec = [&](double e, double k) {
    CollapseSpec spec = base;
    spec.params.e = e;
    spec.params.k = k;
    return spec;
  };
  // What the store holds of each point, in list order, read once: the count stored whole, or the
  // launches kept of it.
  std::vector<std::optional<CollapseResult>> stored_counts;
  std::vector<ResultsStore::KeptLaunches> kept;
  std::size_t total_launches = 0;
  for (double e : es)
    for (double k : ks) {
      const CollapseSpec spec = point_spec(e, k);
      stored_counts.push_back(reader ? reader->find_collapse(spec) : std::nullopt);
      kept.push_back(reader && !stored_counts.back() ? reader->kept_launches(spec) : ResultsStore::KeptLaunches{});
      if (!stored_counts.back()) total_launches += static_cast<std::size_t>(base.realizations) - kept.back().done.size();
    }
  std::size_t launches_done = 0;
  std::uint64_t collisions_done = 0;
  auto report = [&](bool final) {
    const auto now = std::chrono::steady_clock::now();
    if (!final && std::chrono::duration<double>(now - t_last).count() < (tty ? 0.5 : 10.0)) return;
    t_last = now;
    SweepProgress p;
    p.done = launches_done;
    p.total = total_launches;
    p.elapsed = std::chrono::duration<double>(now - t_start).count();
    p.eta = launches_done ? p.elapsed / launches_done * (total_launches - launches_done) : std::nan("");
    p.collisions_per_second = p.elapsed > 0 ? collisions_done / p.elapsed : 0.0;
    p.final = final;
    printer(p);
  };
  LaunchProgress on_launch;
  if (show_progress)
    on_launch = [&](int, std::uint64_t collisions) {
      ++launches_done;
      collisions_done += collisions;
      report(false);
    };
  try {
    for (double e : es) {
      const std::size_t first = results.size();
      for (double k : ks) {
        const CollapseSpec spec = point_spec(e, k);
        CollisionLog log;
        if (events.is_open()) {
          log = [&events, e, k](const std::vector<CollisionRecord>& recs) {
            for (const CollisionRecord& c : recs) {
              events << fmt::format("{},{},{},{},{:.17g},{:.17g},{},{},{:.17g},{:.17g}\n", e, k, c.realization, c.index,
                                    c.t_begin, c.t_end, c.i, c.i + 1, c.speed_in, c.speed_out);
            }
          };
        }
        const std::size_t point = results.size();
        std::optional<CollapseResult>& stored_count = stored_counts[point];
        const std::size_t carried = kept[point].done.size();
        const std::set<std::string> carried_versions = kept[point].code_versions;  // a copy: kept[point] is handed over below
        if (stored_count) {
          stored_count->spec.threads = spec.threads;
          results.push_back(*stored_count);
          read_back_json.push_back(reader->stored_collapse_json(spec));
        } else if (carry) {
          const LaunchCheckpoint checkpoint = ResultsStore::lazy_launch_checkpoint(o.db_path, spec, std::move(kept[point]), writer);
          results.push_back(run_collapse(spec, log, on_launch, {}, nullptr, &checkpoint));
          read_back_json.push_back(std::nullopt);
        } else {
          results.push_back(run_collapse(spec, log, on_launch));
          read_back_json.push_back(std::nullopt);
        }
        const CollapseResult& r = results.back();
        if (show_progress && tty) fmt::print(stderr, "\r{:<100}\r", "");  // the table row replaces the progress line
        if (!o.quiet && !json_stdout) {
          fmt::print("{:>8} {:>10} {:>12} {:>9} {:>7} {:>7} {:>10} {:>8.2f}\n", e, hard ? "inf" : fmt::format("{:g}", k),
                     num(r.n_tot_mean), num(r.n_tot_error), r.n_tot_min, r.n_tot_max,
                     fmt::format("{}/{}", r.collapsed, base.realizations), r.wall_seconds);
          if (stored_count)
            fmt::print("{:>19} (stored in {}: read back, not counted again)\n", "", o.db_path);
          else if (carried > 0)
            fmt::print("{:>19} ({} of {} launches carried over from an earlier sitting, kept in {}{})\n", "", carried,
                       base.realizations, o.db_path,
                       carried_versions.size() == 1 && *carried_versions.begin() == code_version()
                           ? ""
                           : fmt::format("; counted by code version {}, this is {}", fmt::join(carried_versions, ", "), code_version()));
          if (r.grazing_contacts > 0)
            fmt::print("{:>19} ({} of {} collisions began below the engine's resolution, {} of them held; docs/engines.md)\n",
                       "", r.grazing_contacts, r.collisions, r.held_contacts);
          if (r.one_body > 0)
            fmt::print("{:>19} ({} of {} launches ended as one body: every relative velocity below 1e-13 of the speeds; docs/collapse.md)\n",
                       "", r.one_body, base.realizations);
          std::fflush(stdout);
        }
      }
      for (std::size_t i = first; i + 1 < results.size(); ++i) slopes.push_back(k_slope(results[i], results[i + 1]));
    }
    if (show_progress) report(true);
  } catch (const UnphysicalStateError& e) {
    remove_tmp();
    fmt::print(stderr, "granchain: error: the simulation became unphysical: {}; no count was stored or written{}\n", e.what(),
               writer ? fmt::format(" (the launches that finished before it stay in {}, table collapse_launches)", o.db_path) : "");
    return kExitUnphysical;
  } catch (const StoreError& e) {
    remove_tmp();
    fmt::print(stderr, "granchain: error: {}; no count was stored or written (launches kept before it stay in {})\n", e.what(),
               o.db_path);
    return kExitStoreFailed;
  }

  nlohmann::json j;
  j["points"] = nlohmann::json::array();
  for (std::size_t i = 0; i < results.size(); ++i)
    j["points"].push_back(read_back_json[i] ? *read_back_json[i] : collapse_result_to_json(results[i]));
  j["slopes"] = nlohmann::json::array();
  const bool three_body = N == 3 && base.setup == CollapseSetup::FreeSpace;
  if (!slopes.empty() && !o.quiet && !json_stdout) {
    fmt::print("\nslope of n_tot against log10 k (paired over launches){}\n",
               three_body ? "; theory for N = 3: Eq. (ntot-log) -ln10/(2 ln q), all collisions -ln10/ln q" : "");
    fmt::print("{:>8} {:>10} {:>10} {:>10} {:>9} {:>8} {:>8} {:>14} {:>14}\n", "e", "k1", "k2", "slope", "+-", "alpha",
               "+-", "Eq. ntot-log", "all collisions");
  }
  for (const KSlope& s : slopes) {
    const double e = s.e;
    const bool theory_ok = three_body && e < theory::ec3();
    const double paper = theory_ok ? std::log(10.0) * theory::ntot_slope_per_ln_k(e) : std::nan("");
    const double total = theory_ok ? std::log(10.0) * theory::collisions_slope_per_ln_k(e) : std::nan("");
    const auto real = number_or_null;
    j["slopes"].push_back({{"e", e}, {"k1", s.k1}, {"k2", s.k2}, {"slope_per_log10_k", real(s.per_log10_k)},
                           {"error", real(s.error)}, {"launches", s.launches}, {"alpha", real(s.alpha)},
                           {"alpha_error", real(s.alpha_error)}, {"theory_eq_ntot_log", real(paper)},
                           {"theory_all_collisions", real(total)}});
    if (!o.quiet && !json_stdout) {
      fmt::print("{:>8} {:>10g} {:>10g} {:>10} {:>9} {:>8} {:>8} {:>14} {:>14}\n", e, s.k1, s.k2, num(s.per_log10_k),
                 num(s.error), num(s.alpha, "{:.3f}"), num(s.alpha_error, "{:.3f}"), num(paper), num(total));
    }
  }

  // Hard spheres over a list of e: the critical restitution is bracketed by the largest e at which
  // a launch collapsed and the next e of the list, at which none did.
  if (hard && es.size() > 1) {
    double last_collapsing = std::nan(""), next_clean = std::nan("");
    for (std::size_t i = 0; i < results.size(); ++i) {
      if (results[i].collapsed > 0) {
        last_collapsing = results[i].spec.params.e;
        next_clean = i + 1 < results.size() ? results[i + 1].spec.params.e : std::nan("");
      }
    }
    const auto real = number_or_null;
    const double icw = theory::ec_wall_icw(N);
    const double cushion = N >= 2 ? theory::ec_wall_cushion(N) : std::nan("");
    j["critical"] = {{"last_collapsing_e", real(last_collapsing)}, {"next_e_without_collapse", real(next_clean)},
                     {"ec_wall_icw", icw}, {"ec_wall_cushion", cushion}};
    if (base.setup == CollapseSetup::FreeSpace && N >= 3) j["critical"]["ec_free"] = theory::ec_free(N);
    if (!o.quiet && !json_stdout) {
      fmt::print("\ncritical restitution: collapses up to e = {}, none at e = {} (ICW e_c^wall({}) = {:.6f}, cushion {:.6f}{})\n",
                 num(last_collapsing), num(next_clean), N, icw, cushion,
                 base.setup == CollapseSetup::FreeSpace && N >= 3 ? fmt::format(", free-space e_c({}) = {:.6f}", N, theory::ec_free(N)) : "");
    }
  }

  std::string stored;
  if (!o.no_db) {
    announce_on_interrupt(fmt::format("the counts were being stored into {}: each is stored whole or not at all, those "
                                      "stored are kept (a repeat stores each count once); nothing else was written",
                                      o.db_path),
                          events_tmp);
    std::vector<std::int64_t> ids;
    try {
      if (!writer) writer = std::make_shared<ResultsStore>(o.db_path);
      for (const CollapseResult& r : results) ids.push_back(writer->insert_collapse(r));
      j["stored"] = {{"db", o.db_path}, {"collapse_run_ids", ids}};
      stored = fmt::format("{} rows in {} (table collapse_runs)", ids.size(), o.db_path);
    } catch (const StoreError& e) {
      remove_tmp();
      fmt::print(stderr, "granchain: error: {}; {} of {} counts were stored before it, nothing else was written\n", e.what(),
                 ids.size(), results.size());
      return kExitStoreFailed;
    }
  }
  try {
    if (events.is_open()) {
      events.close();
      if (!events) throw std::runtime_error(fmt::format("--events: cannot write '{}'", o.events_path));
      if (!events_direct) std::filesystem::rename(events_tmp, o.events_path);
      stored += (stored.empty() ? "" : ", ") + fmt::format("collisions in {}", o.events_path);
      announce_on_interrupt(fmt::format("written: {}; the JSON may be missing", stored));
    }
    if (json_requested) {
      if (json_stdout) {
        write_standard_output(j.dump(2) + "\n");
      } else {
        write_file_atomically(o.json_path, j.dump(2) + "\n");
        stored += (stored.empty() ? "" : ", ") + fmt::format("JSON in {}", o.json_path);
      }
    }
  } catch (const std::exception& e) {
    remove_tmp();
    fmt::print(stderr, "granchain: error: {}{}\n", e.what(), stored.empty() ? "" : "; already written: " + stored);
    return kExitStoreFailed;
  }
  if (!o.quiet && !json_stdout && !stored.empty()) fmt::print("\nwritten: {}\n", stored);
  return kExitOk;
}

}  // namespace

}  // namespace granchain
