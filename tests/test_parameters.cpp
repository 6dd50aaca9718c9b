// The parameter tables (config/parameter.hpp): typed values and their text resolve to the same
// run, the tables say what the commands take, and the collapse count's reading is one function.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "config/collapse_options.hpp"
#include "config/input_error.hpp"
#include "config/run_options.hpp"
#include "config/run_key.hpp"
#include "sweep/sweep_grid.hpp"

using namespace granchain;

namespace {

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// A Python int, a float or a config file's typed number give the run that their text gives, bit
// for bit; an integer parameter refuses a real number as it refuses "25.0".
TEST(Parameters, TypedValuesResolveAsTheirText) {
  const RunSpec text = resolve_run_options({{"N", "25"}, {"e", "0.88"}, {"k", "1e8"}, {"T", "100"}, {"seed", "7"}}).spec;
  const RunSpec typed = resolve_run_options({{"N", 25LL}, {"e", 0.88}, {"k", 1e8}, {"T", 100LL}, {"seed", 7LL}}).spec;
  EXPECT_EQ(point_key(text), point_key(typed));
  EXPECT_EQ(typed.params.e, 0.88);
  EXPECT_EQ(typed.T, 100.0);
  const std::string m = message_of([] { resolve_run_options({{"N", 25.0}}); });
  EXPECT_NE(m.find("--N = '25.0' is not an integer"), std::string::npos) << m;
  EXPECT_NE(message_of([] { resolve_run_options({{"e", 1.5}}); }).find("--e = 1.5 is out of range; valid range: 0 < e <= 1"),
            std::string::npos);
  EXPECT_NE(message_of([] { resolve_run_options({{"k", std::numeric_limits<double>::infinity()}}); }).find("is not finite"),
            std::string::npos);
  EXPECT_NE(message_of([] { resolve_run_options({{"engine", 3LL}}); }).find("--engine = 3 is not a name"), std::string::npos);
}

// The tables say which parameters a sweep takes lists of, and every entry states its range and
// default in its help.
TEST(Parameters, TablesNameTheSweepAxesAndEveryRange) {
  EXPECT_EQ(sweep_grid_parameters(), (std::vector<std::string>{"N", "e", "k", "T0", "drive", "A", "omega", "Gamma", "f", "T", "engine"}));
  std::set<std::string> names;
  for (const auto* table : {&run_parameters(), &collapse_parameters()})
    for (const Parameter& p : *table) {
      EXPECT_FALSE(p.range.empty()) << p.name;
      EXPECT_NE(p.help().find(p.range), std::string::npos) << p.name;
      if (p.type == ParameterType::Integer || p.type == ParameterType::Real || p.type == ParameterType::RealList)
        EXPECT_TRUE(static_cast<bool>(p.valid)) << p.name << " has no check";
    }
  for (const Parameter& p : run_parameters()) EXPECT_TRUE(names.insert(p.name).second) << p.name << " twice";
}

// granchain collapse and granchain.collapse read one function: defaults, lists, the engine's k.
TEST(Parameters, CollapseOptionsReadListsDefaultsAndTheEnginesK) {
  const CollapseOptions d = resolve_collapse_options({});
  EXPECT_EQ(d.base.params.N, 3);
  EXPECT_EQ(d.es, (std::vector<double>{0.03}));
  EXPECT_EQ(d.ks.size(), 7u);  // 1e4:1e10:x10
  EXPECT_EQ(d.base.rule, StopRule::Ends);
  EXPECT_EQ(d.base.params.g, 0.0);
  const CollapseOptions w = resolve_collapse_options({{"setup", "wall"}, {"e", 0.5}, {"k", "1e6"}, {"N", 4LL}});
  EXPECT_EQ(w.base.rule, StopRule::Strict);
  EXPECT_EQ(w.es, (std::vector<double>{0.5}));
  EXPECT_EQ(w.ks, (std::vector<double>{1e6}));
  const CollapseOptions h = resolve_collapse_options({{"engine", "hard"}, {"tc", 1e-6}});
  EXPECT_TRUE(std::isinf(h.ks.at(0)));
  EXPECT_EQ(h.base.engine.hard.tc, 1e-6);
  EXPECT_NE(message_of([] { resolve_collapse_options({{"engine", "hard"}, {"k", 1e6}}); }).find("leave --k out"), std::string::npos);
  EXPECT_NE(message_of([] { resolve_collapse_options({{"tc", 1e-6}}); }).find("belongs to --engine hard"), std::string::npos);
  EXPECT_NE(message_of([] { resolve_collapse_options({{"stop", "ends"}, {"setup", "wall"}}); }).find("on a wall use --stop strict"),
            std::string::npos);
  EXPECT_NE(message_of([] { resolve_collapse_options({{"realizations", 1LL}}); }).find("--realizations = '1' is out of range"),
            std::string::npos);
  EXPECT_NE(message_of([] { resolve_collapse_options({{"bins", 16LL}}); }).find("unknown parameter 'bins'"), std::string::npos);
}
