#pragma once
// One prepared SQLite statement, finalised on destruction; errors throw StoreError.
#include <sqlite3.h>

#include <cstdint>
#include <fmt/format.h>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

#include "store/results_store.hpp"

namespace granchain {

// Owns one prepared statement.
class SqlStatement {
 public:
  SqlStatement(sqlite3* db, const char* sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK)
      throw StoreError(fmt::format("results store: {}", sqlite3_errmsg(db)));
  }
  ~SqlStatement() { sqlite3_finalize(stmt_); }
  SqlStatement(const SqlStatement&) = delete;
  SqlStatement& operator=(const SqlStatement&) = delete;
  void bind(int i, double x) { sqlite3_bind_double(stmt_, i, x); }
  void bind(int i, std::int64_t x) { sqlite3_bind_int64(stmt_, i, x); }
  void bind(int i, const std::string& s) { sqlite3_bind_text(stmt_, i, s.c_str(), -1, SQLITE_TRANSIENT); }
  // A typed value of a parameter (config/parameter.hpp's TypedValue): text, integer or real.
  void bind(int i, const std::variant<std::string, long long, double>& v) {
    std::visit([&](const auto& x) {
      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, long long>) bind(i, static_cast<std::int64_t>(x));
      else bind(i, x);
    }, v);
  }
  void run() {
    if (sqlite3_step(stmt_) != SQLITE_DONE) throw StoreError(fmt::format("results store: {}", sqlite3_errmsg(db_)));
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  bool row() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw StoreError(fmt::format("results store: {}", sqlite3_errmsg(db_)));
  }
  std::int64_t column_int(int i) { return sqlite3_column_int64(stmt_, i); }
  double column_double(int i) {
    return sqlite3_column_type(stmt_, i) == SQLITE_NULL ? std::numeric_limits<double>::quiet_NaN()
                                                        : sqlite3_column_double(stmt_, i);
  }
  int columns() { return sqlite3_column_count(stmt_); }
  const char* column_name(int i) { return sqlite3_column_name(stmt_, i); }
  int column_type(int i) { return sqlite3_column_type(stmt_, i); }
  sqlite3_value* column_value(int i) { return sqlite3_column_value(stmt_, i); }
  void bind_value(int i, const sqlite3_value* v) { sqlite3_bind_value(stmt_, i, v); }
  void bind_null(int i) { sqlite3_bind_null(stmt_, i); }
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::string column_text(int i) {
    const auto* p = sqlite3_column_text(stmt_, i);
    return p ? reinterpret_cast<const char*>(p) : "";
  }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace granchain
