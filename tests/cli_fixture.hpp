#pragma once
// A test fixture that runs the granchain binary in a fresh folder and captures what it prints.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <vector>
#include <fstream>
#include <sstream>
#include <cstdint>
#include <string>

namespace fs = std::filesystem;

// The first column of the first row of an SQL query on a results store (0 if it fails).
inline std::int64_t query(const fs::path& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  std::int64_t n = 0;
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_busy_timeout(db, 5000);
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW)
      n = sqlite3_column_int64(st, 0);
    sqlite3_finalize(st);
  }
  sqlite3_close(db);
  return n;
}

// Physics columns of every stored run, by point key, from `granchain export` CSV.
inline std::map<std::string, std::string> physics_by_key(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::istringstream h(line);
    for (std::string c; std::getline(h, c, ',');) header.push_back(c);
  }
  const std::vector<std::string> wanted = {"seed",      "n_coll",  "n_coll_err",          "n_coll_blocks", "floor_rate",
                                           "pp_rate",   "samples", "particle_collisions", "floor_hits",    "events"};
  std::map<std::string, std::string> out;
  while (std::getline(in, line)) {
    std::istringstream r(line);
    std::map<std::string, std::string> row;
    std::size_t i = 0;
    for (std::string c; std::getline(r, c, ',');) row[header.at(i++)] = c;
    std::string physics;
    for (const auto& w : wanted) physics += w + "=" + row.at(w) + " ";
    EXPECT_TRUE(out.emplace(row.at("point_key"), physics).second) << "point stored twice: " << row.at("point_key");
  }
  return out;
}

struct CliResult {
  int exit_code;
  std::string out;
  std::string err;
};

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("granchain_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string slurp(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }
  CliResult run(const std::string& args) {
    const std::string cmd = "cd '" + dir_.string() + "' && '" GRANCHAIN_BINARY "' " + args + " > stdout.txt 2> stderr.txt";
    const int status = std::system(cmd.c_str());
    CliResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "stdout.txt"), slurp(dir_ / "stderr.txt")};
    fs::remove(dir_ / "stdout.txt");
    fs::remove(dir_ / "stderr.txt");
    return r;
  }
  // Starts granchain in the test folder without waiting, its output (both streams) in `log` there;
  // returns its process id.
  pid_t start(const std::string& args, const std::string& log = "bg.txt") {
    const std::string cmd = "cd '" + dir_.string() + "' && exec '" GRANCHAIN_BINARY "' " + args + " > " + log + " 2>&1";
    const pid_t pid = fork();
    if (pid == 0) {
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    return pid;
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  // Files the run left in its folder (besides the ones the test wrote).
  std::size_t files() const { return std::distance(fs::directory_iterator(dir_), fs::directory_iterator()); }

  fs::path dir_;
};

