#include "store/stationarity_verdicts.hpp"

#include <sqlite3.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "analysis/blocking.hpp"

namespace granchain {

namespace {

// One half-pair's stored estimates, NaN where the JSON holds null or nothing.
Estimate stored_half(const nlohmann::json& h, const char* value, const char* error) {
  const auto real = [&h](const char* key) {
    return h.contains(key) && h.at(key).is_number() ? h.at(key).get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  return Estimate{real(value), real(error)};
}

// granchain_stationary(stationarity): n_coll's and the mean height's halves judged again.
void judge_stored_halves(sqlite3_context* ctx, int, sqlite3_value** argv) {
  if (sqlite3_value_type(argv[0]) == SQLITE_NULL) {
    sqlite3_result_null(ctx);
    return;
  }
  const auto* text = reinterpret_cast<const char*>(sqlite3_value_text(argv[0]));
  const nlohmann::json s = nlohmann::json::parse(text, nullptr, false);
  if (s.is_discarded() || !s.is_object() || !s.contains("n_coll") || !s.contains("mean_height")) {
    sqlite3_result_null(ctx);
    return;
  }
  bool stationary = true;
  for (const char* quantity : {"n_coll", "mean_height"}) {
    const nlohmann::json& h = s.at(quantity);
    const Estimate first = stored_half(h, "first", "first_err"), second = stored_half(h, "second", "second_err");
    if (std::isnan(first.value) || std::isnan(second.value)) {
      sqlite3_result_null(ctx);
      return;
    }
    stationary = stationary && judge_halves(first, second).stationary;
  }
  sqlite3_result_int(ctx, stationary ? 1 : 0);
}

}  // namespace

void register_stationarity_function(sqlite3* db) {
  sqlite3_create_function_v2(db, "granchain_stationary", 1, SQLITE_UTF8 | SQLITE_DETERMINISTIC, nullptr, judge_stored_halves,
                             nullptr, nullptr, nullptr);
}

std::string current_stationary_sql(const std::string& alias) {
  const std::string json = alias + ".result_json";
  return "COALESCE(granchain_stationary(json_extract(" + json + ", '$.stationarity')), json_extract(" + json +
         ", '$.stationarity.stationary'))";
}

// Each run's JSON judged once (UPDATE ... FROM), the column written only where the verdict changed.
const char* const kRejudgeStoredRuns =
    "UPDATE runs SET stationary = judged.verdict FROM "
    "(SELECT id, granchain_stationary(json_extract(result_json, '$.stationarity')) AS verdict FROM runs) AS judged "
    "WHERE runs.id = judged.id AND judged.verdict IS NOT NULL AND runs.stationary IS NOT judged.verdict;";

}  // namespace granchain
