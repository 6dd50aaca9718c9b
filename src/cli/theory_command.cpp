#include "cli/subcommand.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/input_error.hpp"
#include "provenance.hpp"
#include "store/output_file.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain {

namespace {

struct TheoryFlags {
  std::vector<int> N{2, 3, 4, 5, 10, 25, 100};
  std::vector<double> e{0.01, 0.03, 0.05};
  std::string json_path;
  CLI::Option* json_option = nullptr;
};

int execute_theory(const std::shared_ptr<TheoryFlags>& impl_);

}  // namespace

Subcommand add_theory_command(CLI::App& app) {
  auto impl_ = std::make_shared<TheoryFlags>();
  CLI::App* sub_;
  sub_ = app.add_subcommand("theory", "Print the paper's closed forms for inelastic collapse for given N and e.");
  auto& impl = *impl_;
  sub_->add_option("--N", impl.N, "particle numbers (comma-separated list); integers 1 <= N <= 1e9; default 2,3,4,5,10,25,100")
      ->delimiter(',')
      ->type_name("LIST");
  sub_->add_option("--e", impl.e, "restitution coefficients (comma-separated list); 0 < e < 1; default 0.01,0.03,0.05")
      ->delimiter(',')
      ->type_name("LIST");
  impl.json_option = sub_->add_option("--json", impl.json_path,
                                      "write the values as JSON to FILE, or to standard output if no FILE is given")
                         ->expected(0, 1)
                         ->type_name("[FILE]");
  sub_->footer(
      "Per N: e_c^wall(N) of N hard spheres thrown against an elastic wall from the ICW model, Eq. (icw),\n"
      "tan^2(pi/4 (1 - 1/N)), and its large-N form 1 - pi/N, Eq. (ec_icw_wall); the cushion model's\n"
      "e_c^wall(N), the e where N_c^wall(e) = ln(4/(1-e))/(1-e) equals N, and its large-N form,\n"
      "Eq. (ec_cushion); the free-space estimate e_c(N) = tan^2(pi/4 (1 - 2/N)) of Sec. III.B (N >= 3).\n"
      "Per e: the cushion model's N_c^wall(e); for e <= e_c(3) = 7 - 4 sqrt 3 the three-body fixed points\n"
      "m*, m'* (Appendix A), q, Eq. (def_q), f (Appendix B), and the slope of n_tot against ln k and\n"
      "log10 k, Eq. (ntot-log): -1/(2 ln q). The values are not stored in the results store.\n" +
      exit_codes_help("2 bad input (nothing written)"));
  return {sub_, [impl_] { return execute_theory(impl_); }};
}

namespace {

nlohmann::json theory_json(const std::vector<int>& Ns, const std::vector<double>& es) {
  using namespace theory;
  nlohmann::json j;
  j["ec3"] = ec3();
  j["per_N"] = nlohmann::json::array();
  for (int N : Ns) {
    nlohmann::json row{{"N", N},
                       {"ec_wall_icw", ec_wall_icw(N)},
                       {"ec_wall_icw_asymptotic", ec_wall_icw_asymptotic(N)},
                       {"ec_wall_cushion", N >= 2 ? nlohmann::json(ec_wall_cushion(N)) : nlohmann::json(nullptr)},
                       {"ec_wall_cushion_asymptotic", ec_wall_cushion_asymptotic(N)},
                       {"ec_free", N >= 3 ? nlohmann::json(ec_free(N)) : nlohmann::json(nullptr)}};
    j["per_N"].push_back(row);
  }
  j["per_e"] = nlohmann::json::array();
  for (double e : es) {
    nlohmann::json row{{"e", e}, {"cushion_Nc_wall", cushion_Nc_wall(e)}};
    const bool three_body = e <= ec3();
    const bool slope = e < ec3();
    row["m_star"] = three_body ? nlohmann::json(m_star(e)) : nlohmann::json(nullptr);
    row["m_prime_star"] = three_body ? nlohmann::json(m_prime_star(e)) : nlohmann::json(nullptr);
    row["q"] = three_body ? nlohmann::json(q_ratio(e)) : nlohmann::json(nullptr);
    row["f"] = three_body ? nlohmann::json(f_shift(e)) : nlohmann::json(nullptr);
    row["ntot_slope_per_ln_k"] = slope ? nlohmann::json(ntot_slope_per_ln_k(e)) : nlohmann::json(nullptr);
    row["ntot_slope_per_log10_k"] =
        slope ? nlohmann::json(std::log(10.0) * ntot_slope_per_ln_k(e)) : nlohmann::json(nullptr);
    j["per_e"].push_back(row);
  }
  return j;
}

std::string cell(const nlohmann::json& v) { return v.is_null() ? "-" : fmt::format("{:.6g}", v.get<double>()); }

std::string theory_table(const nlohmann::json& j) {
  std::string out = fmt::format("e_c(3) = 7 - 4 sqrt 3 = {:.10g}\n\n", j["ec3"].get<double>());
  out += fmt::format("{:>8} | {:>12} {:>12} | {:>12} {:>12} | {:>12}\n", "N", "ICW e_c^wall", "1 - pi/N",
                     "cushion", "Eq. ec_cush", "free e_c(N)");
  for (const auto& r : j["per_N"]) {
    out += fmt::format("{:>8} | {:>12} {:>12} | {:>12} {:>12} | {:>12}\n", r["N"].get<int>(), cell(r["ec_wall_icw"]),
                       cell(r["ec_wall_icw_asymptotic"]), cell(r["ec_wall_cushion"]),
                       cell(r["ec_wall_cushion_asymptotic"]), cell(r["ec_free"]));
  }
  out += fmt::format("\n{:>8} | {:>12} | {:>12} {:>12} {:>12} {:>12} | {:>14} {:>14}\n", "e", "N_c^wall", "m*", "m'*",
                     "q", "f", "dn_tot/dln k", "dn_tot/dlog10k");
  for (const auto& r : j["per_e"]) {
    out += fmt::format("{:>8} | {:>12} | {:>12} {:>12} {:>12} {:>12} | {:>14} {:>14}\n", r["e"].get<double>(),
                       cell(r["cushion_Nc_wall"]), cell(r["m_star"]), cell(r["m_prime_star"]), cell(r["q"]),
                       cell(r["f"]), cell(r["ntot_slope_per_ln_k"]), cell(r["ntot_slope_per_log10_k"]));
  }
  return out;
}

}  // namespace

namespace {

int execute_theory(const std::shared_ptr<TheoryFlags>& impl_) {
  auto& impl = *impl_;
  const bool json_requested = impl.json_option->count() > 0;
  const bool json_stdout = json_requested && (impl.json_path.empty() || is_standard_output(impl.json_path));
  try {
    for (int N : impl.N) {
      if (N < 1 || N > 1000000000) throw InputError(fmt::format("--N: {} is out of range; valid: integers 1 <= N <= 1e9", N));
    }
    for (double e : impl.e) {
      if (!(e > 0 && e < 1)) throw InputError(fmt::format("--e: {} is out of range; valid: 0 < e < 1", e));
    }
    if (json_requested && !json_stdout) check_output_file(impl.json_path);
  } catch (const InputError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  nlohmann::json j = theory_json(impl.N, impl.e);
  j["provenance"] = provenance_json();
  try {
    if (json_stdout) {
      write_standard_output(j.dump(2) + "\n");
      return kExitOk;
    }
    if (json_requested) write_file_atomically(impl.json_path, j.dump(2) + "\n");
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitStoreFailed;
  }
  fmt::print("{}", theory_table(j));
  return kExitOk;
}

}  // namespace

}  // namespace granchain
