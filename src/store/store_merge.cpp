#include "store/store_merge.hpp"

#include <sys/stat.h>

#include <cstdio>
#include <memory>
#include <unordered_set>
#include <vector>

#include "config/collapse_options.hpp"
#include "config/run_key.hpp"
#include "store/sqlite_statement.hpp"
#include "store/stationarity_verdicts.hpp"

namespace granchain {

namespace {

// The columns that carry a stored result: equal in two stores for one point unless something
// changed the physics (wall time, date and code version may differ).
const char* kRunResultColumns[] = {"n_coll", "n_coll_err", "n_coll_blocks", "floor_rate", "floor_rate_err", "pp_rate",
                                   "pp_rate_err", "particle_collisions", "floor_hits", "samples", "events"};
// What identifies a collapse count, and what it found.
const char* kCollapseResultColumns[] = {"n_tot", "n_tot_err", "n_tot_min", "n_tot_max", "collapsed"};

struct Connection {
  sqlite3* db = nullptr;
  ~Connection() { sqlite3_close(db); }
};

void exec(sqlite3* db, const char* sql) {
  char* err = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw StoreError("merge: " + msg);
  }
}

int column_index(SqlStatement& st, const std::string& name) {
  for (int i = 0; i < st.columns(); ++i)
    if (name == st.column_name(i)) return i;
  throw StoreError("merge: a source store lacks the column '" + name + "'");
}

// "INSERT INTO table(c1, c2, ...) VALUES(?, ...)" for the first `count` columns of a row,
// leaving out `skip` (the row id, which the target assigns).
std::string insert_sql(const std::string& table, SqlStatement& row, int count, const std::string& skip) {
  std::string names, marks;
  for (int i = 0; i < count; ++i) {
    if (skip == row.column_name(i)) continue;
    names += std::string(names.empty() ? "" : ", ") + row.column_name(i);
    marks += marks.empty() ? "?" : ", ?";
  }
  return "INSERT INTO " + table + "(" + names + ") VALUES(" + marks + ")";
}

void bind_row(SqlStatement& insert, SqlStatement& row, int count, const std::string& skip, int replace_column = -1,
              std::int64_t replacement = 0) {
  int b = 1;
  for (int i = 0; i < count; ++i) {
    if (skip == row.column_name(i)) continue;
    if (i == replace_column) insert.bind(b++, replacement);
    else insert.bind_value(b++, row.column_value(i));
  }
}

std::string describe(SqlStatement& row, int i) {
  switch (row.column_type(i)) {
    case SQLITE_NULL: return "NULL";
    case SQLITE_INTEGER: return std::to_string(row.column_int(i));
    case SQLITE_FLOAT: return fmt::format("{}", row.column_double(i));
    default: return row.column_text(i);
  }
}

// Copies the child rows (profiles, realisations) of one parent.
void copy_children(sqlite3* from, sqlite3* to, const std::string& table, const std::string& parent_column,
                   std::int64_t old_id, std::int64_t new_id) {
  SqlStatement rows(from, ("SELECT * FROM " + table + " WHERE " + parent_column + " = ?").c_str());
  rows.bind(1, old_id);
  std::unique_ptr<SqlStatement> insert;
  int parent = -1;
  while (rows.row()) {
    if (!insert) {
      insert = std::make_unique<SqlStatement>(to, insert_sql(table, rows, rows.columns(), "").c_str());
      parent = column_index(rows, parent_column);
    }
    bind_row(*insert, rows, rows.columns(), "", parent, new_id);
    insert->run();
  }
}

bool has_table(sqlite3* db, const char* name) {
  SqlStatement st(db, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?");
  st.bind(1, std::string(name));
  st.row();
  return st.column_int(0) > 0;
}

// Compares the result columns of a target row with a source row, with one statement prepared
// for the whole merge: SELECT c1 IS ?, c2 IS ?, ..., c1, c2, ... FROM table WHERE id = ?.
class ResultComparer {
 public:
  template <std::size_t n>
  ResultComparer(sqlite3* target, const char* table, const char* (&columns)[n])
      : columns_(columns, columns + n), same_(target, sql(table, columns_).c_str()) {}

  // The first column whose value differs between the target's row `id` and the source row, as
  // "name: target vs source"; "" when all are equal (NULL equals NULL).
  std::string first_difference(std::int64_t id, SqlStatement& row) {
    const int n = static_cast<int>(columns_.size());
    std::vector<int> at;
    for (int c = 0; c < n; ++c) {
      at.push_back(column_index(row, columns_[c]));
      same_.bind_value(c + 1, row.column_value(at.back()));
    }
    same_.bind(n + 1, id);
    same_.row();
    std::string diff;
    for (int c = 0; c < n && diff.empty(); ++c)
      if (same_.column_int(c) == 0) diff = fmt::format("{}: {} vs {}", columns_[c], describe(same_, n + c), describe(row, at[c]));
    same_.reset();
    return diff;
  }

 private:
  static std::string sql(const char* table, const std::vector<const char*>& columns) {
    std::string tests, values;
    for (const char* c : columns) {
      tests += fmt::format("{}{} IS ?", tests.empty() ? "" : ", ", c);
      values += fmt::format(", {}", c);
    }
    return fmt::format("SELECT {}{} FROM {} WHERE id = ?", tests, values, table);
  }
  std::vector<const char*> columns_;
  SqlStatement same_;
};

// The first difference between the profiles of run `target_id` of the target and run `source_id`
// of the source ("particle 3 K: 0.51 vs 0.52", "12 vs 11 particles"), "" when they are identical.
std::string profiles_difference(sqlite3* target, std::int64_t target_id, sqlite3* source, std::int64_t source_id) {
  static const char* kSql = "SELECT i, z_mean, z_mean_err, z_std, z_std_err, K, K_err FROM profiles WHERE run_id = ? ORDER BY i";
  SqlStatement a(target, kSql), b(source, kSql);
  a.bind(1, target_id);
  b.bind(1, source_id);
  for (int rows = 0;; ++rows) {
    const bool ra = a.row(), rb = b.row();
    if (!ra && !rb) return "";
    if (ra != rb) {
      int na = rows + ra, nb = rows + rb;
      while (ra && a.row()) ++na;
      while (rb && b.row()) ++nb;
      return fmt::format("profiles: {} vs {} particles", na, nb);
    }
    for (int c = 0; c < a.columns(); ++c) {
      const bool same = a.column_type(c) == b.column_type(c) &&
                        (a.column_type(c) == SQLITE_NULL || a.column_double(c) == b.column_double(c));
      if (!same)
        return fmt::format("profile of particle {}, {}: {} vs {}", a.column_int(0), a.column_name(c), describe(a, c), describe(b, c));
    }
  }
}

void merge_runs(sqlite3* target, sqlite3* source, const std::string& source_path, const std::string& target_path,
                MergeReport& report) {
  const bool keyed = has_table(source, "run_points");
  SqlStatement rows(source, keyed ? "SELECT r.*, p.point_key, p.sweep_seed, p.replica FROM runs r "
                                    "LEFT JOIN run_points p ON p.run_id = r.id ORDER BY r.id"
                                  : "SELECT r.*, NULL, NULL, NULL FROM runs r ORDER BY r.id");
  const int run_columns = rows.columns() - 3;
  SqlStatement find(target, "SELECT run_id FROM run_points WHERE point_key = ?");
  SqlStatement collapsed(target, "SELECT t FROM collapsed_points WHERE point_key = ?");
  SqlStatement add_key(target, "INSERT INTO run_points(point_key, run_id, sweep_seed, replica) VALUES(?,?,?,?)");
  ResultComparer compare(target, "runs", kRunResultColumns);
  std::unique_ptr<SqlStatement> insert;
  while (rows.row()) {
    const std::int64_t old_id = rows.column_int(column_index(rows, "id"));
    const bool has_key = rows.column_type(run_columns) != SQLITE_NULL;
    if (has_key) {
      const std::string key = rows.column_text(run_columns);
      collapsed.bind(1, key);
      if (collapsed.row()) {
        const double t = collapsed.column_double(0);
        collapsed.reset();
        throw MergeConflict(fmt::format("merge: conflicting results for point '{}': a collapse at t = {} in '{}', and run {} in '{}'; "
                                        "nothing was merged",
                                        key, t, target_path, old_id, source_path));
      }
      collapsed.reset();
      find.bind(1, key);
      const bool found = find.row();
      const std::int64_t existing = found ? find.column_int(0) : 0;
      find.reset();
      if (found) {
        std::string diff = compare.first_difference(existing, rows);
        if (diff.empty()) diff = profiles_difference(target, existing, source, old_id);
        if (!diff.empty())
          throw MergeConflict(fmt::format("merge: conflicting results for point '{}': run {} of '{}' and run {} of '{}' "
                                          "differ ({}); nothing was merged",
                                          key, existing, target_path, old_id, source_path, diff));
        ++report.runs_already_there;
        continue;
      }
    }
    if (!insert) insert = std::make_unique<SqlStatement>(target, insert_sql("runs", rows, run_columns, "id").c_str());
    bind_row(*insert, rows, run_columns, "id");
    insert->run();
    const std::int64_t new_id = sqlite3_last_insert_rowid(target);
    copy_children(source, target, "profiles", "run_id", old_id, new_id);
    if (has_key) {
      add_key.bind_value(1, rows.column_value(run_columns));
      add_key.bind(2, new_id);
      add_key.bind_value(3, rows.column_value(run_columns + 1));
      add_key.bind_value(4, rows.column_value(run_columns + 2));
      add_key.run();
    }
    ++report.runs_added;
  }
}

void merge_collapse(sqlite3* target, sqlite3* source, const std::string& source_path, const std::string& target_path,
                    MergeReport& report) {
  SqlStatement rows(source, "SELECT * FROM collapse_runs ORDER BY id");
  std::string where;
  for (const std::string& c : collapse_identity_columns()) where += fmt::format("{}{} IS ?", where.empty() ? "" : " AND ", c);
  SqlStatement find(target, ("SELECT id FROM collapse_runs WHERE " + where).c_str());
  ResultComparer compare(target, "collapse_runs", kCollapseResultColumns);
  std::unique_ptr<SqlStatement> insert;
  while (rows.row()) {
    const std::int64_t old_id = rows.column_int(column_index(rows, "id"));
    int b = 1;
    for (const std::string& c : collapse_identity_columns()) find.bind_value(b++, rows.column_value(column_index(rows, c)));
    const bool found = find.row();
    const std::int64_t existing = found ? find.column_int(0) : 0;
    find.reset();
    if (found) {
      const std::string diff = compare.first_difference(existing, rows);
      if (!diff.empty())
        throw MergeConflict(fmt::format("merge: conflicting collapse counts: collapse run {} of '{}' and {} of '{}' have the "
                                        "same parameters and seed but differ ({}); nothing was merged",
                                        existing, target_path, old_id, source_path, diff));
      ++report.collapse_already_there;
      continue;
    }
    if (!insert) insert = std::make_unique<SqlStatement>(target, insert_sql("collapse_runs", rows, rows.columns(), "id").c_str());
    bind_row(*insert, rows, rows.columns(), "id");
    insert->run();
    copy_children(source, target, "collapse_realizations", "run_id", old_id, sqlite3_last_insert_rowid(target));
    ++report.collapse_added;
  }
}

// Collapsed points (hard spheres that collapsed at a sweep point) by key: a key that the target
// holds as a run, or as a collapse at another instant, is a conflict.
void merge_collapsed_points(sqlite3* target, sqlite3* source, const std::string& source_path, const std::string& target_path,
                            MergeReport& report) {
  if (!has_table(source, "collapsed_points")) return;
  SqlStatement rows(source, "SELECT point_key, created_utc, code_version, t, first_particle, last_particle, collisions, message "
                            "FROM collapsed_points ORDER BY point_key");
  SqlStatement as_run(target, "SELECT run_id FROM run_points WHERE point_key = ?");
  SqlStatement as_collapse(target, "SELECT t, collisions FROM collapsed_points WHERE point_key = ?");
  SqlStatement insert(target, "INSERT INTO collapsed_points(point_key, created_utc, code_version, t, first_particle, last_particle, "
                              "collisions, message) VALUES(?,?,?,?,?,?,?,?)");
  while (rows.row()) {
    const std::string key = rows.column_text(0);
    as_run.bind(1, key);
    const bool run = as_run.row();
    const std::int64_t run_id = run ? as_run.column_int(0) : 0;
    as_run.reset();
    if (run)
      throw MergeConflict(fmt::format("merge: conflicting results for point '{}': run {} of '{}', and a collapse at t = {} in '{}'; "
                                      "nothing was merged",
                                      key, run_id, target_path, rows.column_double(3), source_path));
    as_collapse.bind(1, key);
    if (as_collapse.row()) {
      const bool same = as_collapse.column_double(0) == rows.column_double(3) && as_collapse.column_int(1) == rows.column_int(6);
      const double t = as_collapse.column_double(0);
      as_collapse.reset();
      if (!same)
        throw MergeConflict(fmt::format("merge: conflicting collapses for point '{}': t = {} in '{}', t = {} in '{}'; nothing was "
                                        "merged",
                                        key, t, target_path, rows.column_double(3), source_path));
      ++report.collapsed_already_there;
      continue;
    }
    as_collapse.reset();
    for (int c = 0; c < 8; ++c) insert.bind_value(c + 1, rows.column_value(c));
    insert.run();
    insert.reset();
    ++report.collapsed_added;
  }
}

// The count_key of every count the target holds whole (collapse_runs): their launches are spent.
std::unordered_set<std::string> whole_count_keys(sqlite3* target) {
  const std::vector<const Parameter*> stored = stored_collapse_parameters();
  std::string names;
  for (const Parameter* p : stored) names += (names.empty() ? "" : ", ") + p->store_column;
  SqlStatement counts(target, ("SELECT " + names + " FROM collapse_runs").c_str());
  std::unordered_set<std::string> keys;
  while (counts.row()) {
    std::vector<TypedValue> values;
    for (std::size_t i = 0; i < stored.size(); ++i) {
      const int c = static_cast<int>(i);
      switch (stored[i]->type) {
        case ParameterType::Integer: values.emplace_back(static_cast<long long>(counts.column_int(c))); break;
        case ParameterType::Real:
        case ParameterType::RealList: values.emplace_back(counts.column_double(c)); break;
        default: values.emplace_back(counts.column_text(c)); break;
      }
    }
    keys.insert(collapse_key(values));
  }
  return keys;
}

// The launches of counts not yet stored whole (collapse_launches): copied unless the target holds
// the count whole or the same launch already; the same launch with other numbers is a conflict
// (the physics changed between the two).
void merge_kept_launches(sqlite3* target, sqlite3* source, const std::string& source_path, const std::string& target_path,
                         MergeReport& report) {
  if (!has_table(source, "collapse_launches")) return;
  const std::unordered_set<std::string> whole = whole_count_keys(target);
  const char* columns = "count_key, realization, created_utc, code_version, sitting, sitting_seconds, particle_collisions, "
                        "wall_hits, collapsed, t_stop, grazing_contacts, held_contacts, one_body, seconds";
  SqlStatement rows(source, fmt::format("SELECT {} FROM collapse_launches ORDER BY count_key, realization", columns).c_str());
  SqlStatement there(target, "SELECT particle_collisions, wall_hits, collapsed, t_stop, grazing_contacts, held_contacts, one_body "
                             "FROM collapse_launches WHERE count_key = ? AND realization = ?");
  SqlStatement insert(target, fmt::format("INSERT INTO collapse_launches({}) VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?)", columns).c_str());
  while (rows.row()) {
    if (whole.count(rows.column_text(0)) > 0) {
      ++report.launches_already_there;
      continue;
    }
    there.bind_value(1, rows.column_value(0));
    there.bind_value(2, rows.column_value(1));
    if (there.row()) {
      bool same = there.column_double(3) == rows.column_double(9);  // t_stop; the counts below
      for (int c : {0, 1, 2, 4, 5, 6}) same = same && there.column_int(c) == rows.column_int(c + 6);
      there.reset();
      if (!same)
        throw MergeConflict(fmt::format("merge: conflicting launches: launch {} of '{}' differs between '{}' and '{}'; nothing was merged",
                                        rows.column_int(1), rows.column_text(0), target_path, source_path));
      ++report.launches_already_there;
      continue;
    }
    there.reset();
    for (int c = 0; c < 14; ++c) insert.bind_value(c + 1, rows.column_value(c));
    insert.run();
    insert.reset();
    ++report.launches_added;
  }
}

// The target's own kept launches of counts it now holds whole are deleted, as storing a count does.
void drop_spent_launches(sqlite3* target) {
  SqlStatement drop(target, "DELETE FROM collapse_launches WHERE count_key = ?");
  for (const std::string& key : whole_count_keys(target)) {
    drop.bind(1, key);
    drop.run();
    drop.reset();
  }
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  return stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

MergeReport merge_into(const std::string& target, const std::vector<std::string>& sources) {
  ResultsStore out(target);
  sqlite3* db = out.handle();
  MergeReport report;
  exec(db, "BEGIN IMMEDIATE");
  try {
    for (const auto& path : sources) {
      Connection src;
      if (sqlite3_open_v2(path.c_str(), &src.db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK)
        throw StoreError(fmt::format("merge: cannot open '{}'", path));
      sqlite3_busy_timeout(src.db, 60000);
      exec(src.db, "BEGIN");  // one consistent snapshot of the source
      merge_runs(db, src.db, path, target, report);
      merge_collapse(db, src.db, path, target, report);
      merge_collapsed_points(db, src.db, path, target, report);
      merge_kept_launches(db, src.db, path, target, report);
      exec(src.db, "COMMIT");
    }
    drop_spent_launches(db);
    exec(db, kVersion1RunsToVersion2);  // rows merged from a version-1 source
    exec(db, kRunsVerdictsFromJson);    // rows merged from a source older than version 3
    exec(db, kRejudgeStoredRuns);       // rows judged under an earlier rule
    exec(db, "COMMIT");
  } catch (...) {
    sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  return report;
}

}  // namespace

MergeReport merge_stores(const std::string& target, const std::vector<std::string>& sources) {
  for (const auto& s : sources) {
    struct stat st {};
    if (stat(s.c_str(), &st) != 0) throw StoreError(fmt::format("merge: source '{}' does not exist", s));
    if (same_file(s, target)) throw StoreError(fmt::format("merge: source '{}' is the target itself", s));
    ResultsStore::preflight(s, ResultsStore::Access::ReadOnly, "merge source");
  }
  ResultsStore::preflight(target, ResultsStore::Access::ReadWrite, "--into");
  struct stat st {};
  const bool existed = stat(target.c_str(), &st) == 0;
  try {
    return merge_into(target, sources);
  } catch (...) {
    if (!existed) std::remove(target.c_str());  // a failed merge leaves no new file behind
    try {
      throw;
    } catch (const MergeConflict&) {
      throw;
    } catch (const StoreError& e) {  // past the checks above: the stores could not be written or read
      throw MergeWriteError(fmt::format("{}; nothing was merged", e.what()));
    }
  }
}

}  // namespace granchain
