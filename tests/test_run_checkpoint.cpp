// A run saved part way and resumed (simulation/driven_run.hpp, RunResumption; store/run_checkpoint.hpp)
// gives bit for bit the result of the run that was never stopped: the engine, the floor's random
// generator and every observer carry on as if nothing had happened. Stopped in the transient and in
// the window, once and twice, on the thermal floor and above a vibrating plate, for each resumable
// engine; the saved state read back through its file; states of another run refused; and the
// command line: a SIGTERM saves, the same command resumes to the uninterrupted run's numbers.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <thread>

#include "cli_fixture.hpp"
#include "config/run_key.hpp"
#include "engines/engine_registry.hpp"
#include "engines/fine_time.hpp"
#include "model/state_archive.hpp"
#include "simulation/cancellation.hpp"
#include "simulation/driven_run.hpp"
#include "store/run_checkpoint.hpp"
#include "store/run_json.hpp"

using namespace granchain;

namespace {

RunSpec column(EngineKind engine, DriveKind drive) {
  RunSpec s;
  s.params.N = 6;
  s.params.e = 0.7;
  s.params.k = 1e4;
  s.engine.kind = engine;
  s.engine.hard.tc = 1e-3;  // hard spheres: the TC model keeps them from collapsing (and is saved too)
  if (drive != DriveKind::Thermal) s.drive = DriveSpec{drive, 0.1, 5.0};
  s.T = 40.0;
  s.transient = 10.0;
  s.seed = 17;
  return s;
}

// Everything a run measured and how much work it did, without its timings.
std::string physics(const RunResult& r) {
  nlohmann::json j = run_result_to_json(r);
  j.erase("cost");
  j["steps"] = r.steps;
  j["events"] = r.events;
  return j.dump();
}

// Runs spec and stops it (RunCancelled) at the progress report number `stop_at` (reported at every
// chunk of the transient and every sample), keeping the state saved then; nothing if it finished.
std::optional<StateArchive> run_until(const RunSpec& spec, int stop_at, const StateArchive* resume_from = nullptr) {
  std::optional<StateArchive> saved;
  RunResumption resumption;
  resumption.resume_from = resume_from;
  resumption.every = 1e9;  // only the save at the stop
  resumption.save = [&](const StateArchive& a) { saved = a; };
  int reports = 0;
  try {
    run_driven_column(spec, [&](const RunProgress&) {
      if (++reports == stop_at) throw RunCancelled{};
    }, 0.0, resumption);
  } catch (const RunCancelled&) {
    return saved;
  }
  return std::nullopt;
}

struct Case {
  EngineKind engine;
  DriveKind drive;
  double start_k = 0.0;  // hard spheres after a soft start: the exact engine at this k runs the transient
};

class ResumedRun : public ::testing::TestWithParam<Case> {};

}  // namespace

// Stopped at a chunk of the transient (report 4: t = 4 of 10) and at a sample of the window (report
// 1500: t = 10 + 14.9), each saved state resumed to the end gives the uninterrupted run's result to
// the last bit; so does a run stopped twice (the second stop in its resumed part).
TEST_P(ResumedRun, GivesTheUninterruptedRunsResultBitForBit) {
  RunSpec spec = column(GetParam().engine, GetParam().drive);
  spec.engine.start_k = GetParam().start_k;
  const std::string whole = physics(run_driven_column(spec));

  for (int stop_at : {4, 1500}) {
    SCOPED_TRACE(stop_at);
    const std::optional<StateArchive> saved = run_until(spec, stop_at);
    ASSERT_TRUE(saved.has_value()) << "the run was not stopped: the test would show nothing";
    const SavedRunPlace place = saved_run_place(*saved);
    EXPECT_GT(place.t, 0.0);
    EXPECT_LT(place.t, spec.transient + spec.T);
    EXPECT_EQ(place.in_window, stop_at > 10);
    RunResumption resumption;
    resumption.resume_from = &*saved;
    EXPECT_EQ(physics(run_driven_column(spec, {}, 0.5, resumption)), whole);
  }
  // Twice: stopped in the transient, resumed, stopped again in the window (its 1000th report after
  // the resumption), resumed to the end.
  const std::optional<StateArchive> first = run_until(spec, 3);
  ASSERT_TRUE(first.has_value());
  const std::optional<StateArchive> second = run_until(spec, 1000, &*first);
  ASSERT_TRUE(second.has_value());
  EXPECT_GT(saved_run_place(*second).t, saved_run_place(*first).t);
  RunResumption resumption;
  resumption.resume_from = &*second;
  EXPECT_EQ(physics(run_driven_column(spec, {}, 0.5, resumption)), whole);
}

INSTANTIATE_TEST_SUITE_P(ResumableEngines, ResumedRun,
                         ::testing::Values(Case{EngineKind::Reference, DriveKind::Thermal},
                                           Case{EngineKind::ReferenceLocated, DriveKind::Thermal},
                                           Case{EngineKind::Reference, DriveKind::Sine},
                                           Case{EngineKind::ReferenceLocated, DriveKind::Sawtooth},
                                           Case{EngineKind::Exact, DriveKind::Thermal}, Case{EngineKind::Exact, DriveKind::Sine},
                                           Case{EngineKind::Exact, DriveKind::Sawtooth}, Case{EngineKind::Hard, DriveKind::Thermal},
                                           Case{EngineKind::Hard, DriveKind::Sawtooth}, Case{EngineKind::Hard, DriveKind::Thermal, 1e5}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = std::string(engine_name(info.param.engine)) + "_" +
                                              (info.param.drive == DriveKind::Thermal ? "thermal"
                                               : info.param.drive == DriveKind::Sine  ? "sine"
                                                                                      : "sawtooth");
                           if (info.param.start_k > 0) name += "_soft_start";
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// The event-driven engines in a condensed column (N = 40, e = 0.3): the exact engine at k = 1e7
// (clusters of tens of particles, contacts of up to 40 tau_c, searches that resume at refresh
// events), on the thermal floor and on a sine plate (its grounded cluster, the mirror modes and their
// particular solution), and hard spheres under the TC model with t_c = 1e-2, about the time between
// a particle's collisions here (a collision within t_c of the particle's last one is elastic, so that
// memory is part of the state). Stopped in the transient and at three places of the window, each
// resumed run ends with the uninterrupted run's numbers; and so does a run stopped and resumed every
// 37 reports, 27 times over (each field of the state that a restore got wrong would show in one of
// them).
class CondensedColumn : public ::testing::TestWithParam<Case> {};

TEST_P(CondensedColumn, ResumesBitForBit) {
  RunSpec spec;
  spec.params.N = 40;
  spec.params.e = 0.3;
  spec.params.k = 1e7;
  spec.engine.kind = GetParam().engine;
  spec.engine.hard.tc = 1e-2;
  if (GetParam().drive != DriveKind::Thermal) spec.drive = DriveSpec{GetParam().drive, 0.1, 5.0};
  spec.T = 10.0;
  spec.transient = 5.0;
  spec.seed = 17;
  const RunResult whole = run_driven_column(spec);
  ASSERT_GT(whole.particle_collisions, 5000u);
  for (int stop_at : {3, 37, 500, 999}) {
    SCOPED_TRACE(stop_at);
    const std::optional<StateArchive> saved = run_until(spec, stop_at);
    ASSERT_TRUE(saved.has_value());
    RunResumption resumption;
    resumption.resume_from = &*saved;
    EXPECT_EQ(physics(run_driven_column(spec, {}, 0.5, resumption)), physics(whole));
  }
  std::optional<StateArchive> state;
  std::optional<RunResult> last;
  int sittings = 0;
  while (!last && sittings < 100) {
    ++sittings;
    RunResumption resumption;
    resumption.resume_from = state ? &*state : nullptr;
    resumption.every = 1e9;
    std::optional<StateArchive> saved;
    resumption.save = [&](const StateArchive& a) { saved = a; };
    int reports = 0;
    try {
      last = run_driven_column(spec, [&](const RunProgress&) {
        if (++reports == 37) throw RunCancelled{};
      }, 0.0, resumption);
    } catch (const RunCancelled&) {
      ASSERT_TRUE(saved.has_value());
      state = std::move(saved);
    }
  }
  ASSERT_TRUE(last.has_value());
  EXPECT_GE(sittings, 25);
  EXPECT_EQ(physics(*last), physics(whole));
}

INSTANTIATE_TEST_SUITE_P(EventDrivenEngines, CondensedColumn,
                         ::testing::Values(Case{EngineKind::Exact, DriveKind::Thermal}, Case{EngineKind::Exact, DriveKind::Sine},
                                           Case{EngineKind::Hard, DriveKind::Thermal}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           const char* drive = info.param.drive == DriveKind::Thermal ? "_thermal" : "_sine";
                           return std::string(engine_name(info.param.engine)) + drive;
                         });

// The resumption depends on the saved state, not only on the spec: a state saved by a run with
// another seed, resumed under this run's spec, ends elsewhere (the floor's generator and the column
// come from the state), and saving as it goes (at every sample) leaves the result untouched.
TEST(RunCheckpoint, TheStateCarriesTheRunAndSavingDoesNotDisturbIt) {
  const RunSpec spec = column(EngineKind::Reference, DriveKind::Thermal);
  const std::string whole = physics(run_driven_column(spec));
  RunSpec other = spec;
  other.seed = 18;
  const std::optional<StateArchive> foreign = run_until(other, 1500);
  ASSERT_TRUE(foreign.has_value());
  RunResumption from_foreign;
  from_foreign.resume_from = &*foreign;
  EXPECT_NE(physics(run_driven_column(spec, {}, 0.5, from_foreign)), whole);

  int saves = 0;
  RunResumption every_sample;
  every_sample.every = 0.0;
  every_sample.save = [&](const StateArchive&) { ++saves; };
  const RunResult saved_as_it_went = run_driven_column(spec, {}, 0.5, every_sample);
  EXPECT_EQ(physics(saved_as_it_went), whole);
  EXPECT_EQ(saves, 10 + saved_as_it_went.samples);  // each of the transient's 10 chunks and every sample
}

// Through its file: written as CBOR and read back, the state resumes to the same result; the key
// and the writer come back as written.
TEST(RunCheckpoint, TheFileKeepsTheStateWhole) {
  const RunSpec spec = column(EngineKind::Reference, DriveKind::Thermal);
  const std::optional<StateArchive> saved = run_until(spec, 2000);
  ASSERT_TRUE(saved.has_value());
  const fs::path file = fs::temp_directory_path() / ("granchain_checkpoint_" + std::to_string(::getpid()) + ".ckpt");
  write_run_checkpoint(file.string(), {point_key(spec), "test-writer", *saved});
  const std::optional<RunCheckpoint> back = read_run_checkpoint(file.string());
  fs::remove(file);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->key, point_key(spec));
  EXPECT_EQ(back->written_by, "test-writer");
  EXPECT_EQ(back->state, *saved);
  RunResumption resumption;
  resumption.resume_from = &back->state;
  EXPECT_EQ(physics(run_driven_column(spec, {}, 0.5, resumption)), physics(run_driven_column(spec)));
  EXPECT_FALSE(read_run_checkpoint(file.string()).has_value());  // no file: nothing to resume
}

// A state that does not fit the run is refused, never resumed: another N (the arrays' lengths),
// another window (its samples), a file that is not a checkpoint.
TEST(RunCheckpoint, AStateThatDoesNotFitIsRefused) {
  const RunSpec spec = column(EngineKind::Reference, DriveKind::Thermal);
  const std::optional<StateArchive> saved = run_until(spec, 1500);
  ASSERT_TRUE(saved.has_value());
  RunResumption resumption;
  resumption.resume_from = &*saved;
  RunSpec more = spec;
  more.params.N = 7;
  EXPECT_THROW(run_driven_column(more, {}, 0.5, resumption), StateArchiveError);
  RunSpec longer = spec;
  longer.T = 80.0;
  EXPECT_THROW(run_driven_column(longer, {}, 0.5, resumption), StateArchiveError);

  const fs::path file = fs::temp_directory_path() / ("granchain_not_checkpoint_" + std::to_string(::getpid()));
  std::ofstream(file) << "{\"format\": \"something else\"}";
  EXPECT_THROW(read_run_checkpoint(file.string()), CheckpointError);
  fs::remove(file);

}

// An event-driven engine's state that does not hold together (a corrupted file, another build's
// layout) is refused before any event acts on it, never followed out of the engine's arrays.
TEST(RunCheckpoint, ACorruptedEventDrivenStateIsRefused) {
  RunSpec spec;
  spec.params.N = 40;
  spec.params.e = 0.1;  // a near-solid: clusters of many particles at every instant
  spec.params.k = 1e5;
  spec.engine.kind = EngineKind::Exact;
  spec.T = 10.0;
  spec.transient = 5.0;
  spec.seed = 17;
  const std::optional<StateArchive> saved = run_until(spec, 500);
  ASSERT_TRUE(saved.has_value());
  const StateArchive& engine = saved->at("engine");
  const auto slots = static_cast<std::size_t>(saved->at("engine").at("slot_kind").get_binary().size());
  const auto times = unpack_array<FineTime>(engine, "slot_time", slots);
  const auto kinds = unpack_array<std::uint8_t>(engine, "slot_kind", slots);
  const auto pairs = unpack_array<int>(engine, "slot_pair", slots);
  const auto hi = unpack_array<int>(engine, "hi", 40);
  // The first cluster of two or more with a pending contact end, and an open pair's gap slot.
  std::size_t cluster = slots;
  for (std::size_t lo = 0; lo < 40; lo = static_cast<std::size_t>(hi[lo]) + 1)
    if (hi[lo] > static_cast<int>(lo) && kinds[lo] == 1 && cluster == slots) cluster = lo;
  ASSERT_LT(cluster, slots) << "no cluster with a pending contact end: the test would show nothing";

  // Each corruption is refused with the line that names it.
  const auto refused = [&](const char* what, const std::function<void(StateArchive&)>& corrupt) {
    SCOPED_TRACE(what);
    StateArchive bad = *saved;
    corrupt(bad.at("engine"));
    RunResumption resumption;
    resumption.resume_from = &bad;
    try {
      run_driven_column(spec, {}, 0.5, resumption);
      ADD_FAILURE() << "resumed";
    } catch (const StateArchiveError& error) {
      EXPECT_NE(std::string(error.what()).find(what), std::string::npos) << error.what();
    }
  };
  refused("of another layout", [](StateArchive& e) { e["layout"] = 2; });
  refused("a cluster's event at a pair outside it", [&](StateArchive& e) {
    std::vector<int> p = pairs;
    p[cluster] = hi[cluster] + 5;
    e["slot_pair"] = pack_array(p);
  });
  refused("an event before the engine's time", [&](StateArchive& e) {
    std::vector<FineTime> t = times;
    t[cluster] = FineTime(1.0);
    e["slot_time"] = pack_array(t);
  });
  refused("an event at no time", [&](StateArchive& e) {
    std::vector<FineTime> t = times;
    t[cluster] = FineTime(std::nan(""));
    e["slot_time"] = pack_array(t);
  });
  refused("a cluster's event at a particle that is not a cluster's lowest", [&](StateArchive& e) {
    std::vector<FineTime> t = times;
    std::vector<std::uint8_t> k = kinds;
    t[cluster + 1] = t[cluster];
    k[cluster + 1] = k[cluster];
    e["slot_time"] = pack_array(t);
    e["slot_kind"] = pack_array(k);
  });
  refused("clusters do not tile the chain", [&](StateArchive& e) {
    std::vector<int> h = hi;
    h[0] = 45;
    e["hi"] = pack_array(h);
  });
  refused("a cluster formed after the last formation", [](StateArchive& e) { e["formations"] = 0; });

  RunSpec hard = spec;
  hard.engine.kind = EngineKind::Hard;
  hard.engine.hard.tc = 1e-2;
  const std::optional<StateArchive> hard_saved = run_until(hard, 500);
  ASSERT_TRUE(hard_saved.has_value());
  StateArchive bad = *hard_saved;
  const std::size_t watched = bad.at("engine").at("ring_pair").get_binary().size() / sizeof(int);
  std::vector<int> ring = unpack_array<int>(bad.at("engine"), "ring_pair", watched);
  ring[0] = 40;
  bad["engine"]["ring_pair"] = pack_array(ring);
  RunResumption resumption;
  resumption.resume_from = &bad;
  EXPECT_THROW(run_driven_column(hard, {}, 0.5, resumption), StateArchiveError);
}

// The registry's word and the engines agree: a resumable engine saves and restores, the others
// refuse to.
TEST(RunCheckpoint, TheRegistrySaysWhichEnginesCanSave) {
  const RunSpec spec = column(EngineKind::Reference, DriveKind::Thermal);
  ChainState s;
  s.z = {0.5, 1.6, 2.7};
  s.v = {0.1, -0.2, 0.3};
  ChainParameters p = spec.params;
  p.N = 3;
  Wall wall;
  for (const EngineInfo& e : engines()) {
    SCOPED_TRACE(e.name);
    EngineChoice choice;
    choice.kind = e.kind;
    const auto engine = make_engine(choice, p, s, &wall);
    StateArchive a;
    if (e.resumable) {
      EXPECT_NO_THROW(engine->save(a));
      EXPECT_NO_THROW(engine->restore(a));
    } else {
      EXPECT_THROW(engine->save(a), std::logic_error);
    }
  }
}

namespace {
class RunCheckpointCli : public Cli {};
// The run of `run --engine reference --N 3 --T 200 --transient 0 --seed 1`.
RunSpec three_particles() {
  RunSpec s;
  s.params.N = 3;
  s.engine.kind = EngineKind::Reference;
  s.T = 200;
  s.transient = 0;
  s.seed = 1;
  return s;
}
// The measured part of a run's JSON (its cost, provenance and code version left out).
std::string measured(const std::string& json_text) {
  nlohmann::json j = nlohmann::json::parse(json_text);
  for (const char* k : {"cost", "provenance", "code_version", "stored"}) j.erase(k);
  return j.dump();
}
}  // namespace

// Bad input: one line naming the parameter and what is valid, exit code 2, nothing written.
TEST_F(RunCheckpointCli, WhatCannotBeCheckpointedIsRefused) {
  struct Bad {
    std::string args, expect;
  };
  for (const Bad& b : std::vector<Bad>{
           {"--checkpoint-every 60", "--checkpoint-every = 60: it acts only with --checkpoint FILE"},
           {"--engine reference --checkpoint c.ckpt --checkpoint-every 0.5", "1 <= checkpoint-every <= 1e7"},
       }) {
    SCOPED_TRACE(b.args);
    const CliResult r = run("run --N 3 --T 2 --transient 0 -q --db r.db " + b.args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(b.expect), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(files(), 0u);
  }
  // A checkpoint of another run is not resumed under this one.
  const std::string other = "run --engine reference --N 3 --T 200 --transient 0 --seed 1 --no-db -q --checkpoint c.ckpt";
  ASSERT_EQ(run(other + " --checkpoint-every 1").exit_code, 0);  // finished: its checkpoint is removed
  EXPECT_FALSE(fs::exists(dir_ / "c.ckpt"));
  const RunSpec three = three_particles();
  const std::optional<StateArchive> saved = run_until(three, 50);
  ASSERT_TRUE(saved.has_value());
  write_run_checkpoint((dir_ / "c.ckpt").string(), {point_key(three), "test", *saved});
  const CliResult r = run("run --engine reference --N 3 --T 200 --transient 0 --seed 2 --no-db -q --checkpoint c.ckpt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holds the state of another run"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "c.ckpt"));  // left for the run it belongs to
}

// SIGTERM (a batch system's end of a job) in the middle of a run with --checkpoint: the run saves
// its state and ends by the signal, saying where it stopped; the same command resumes it and
// prints the numbers of the run that was never stopped, and removes the spent checkpoint.
TEST_F(RunCheckpointCli, SigtermSavesAndTheSameCommandResumesToTheSameNumbers) {
  const std::string args = "run --engine reference --N 20 --e 0.5 --k 1e7 --T 150 --transient 20 --seed 5 --no-db -q";
  ASSERT_EQ(run(args + " --json whole.json").exit_code, 0);

  const pid_t pid = start(args + " --json resumed.json --checkpoint c.ckpt");
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const std::string log = slurp(dir_ / "bg.txt");
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "the run ended before the signal: " << log;
  EXPECT_NE(log.find("interrupted by SIGTERM; the run's state at t = "), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(dir_ / "c.ckpt"));
  EXPECT_FALSE(fs::exists(dir_ / "resumed.json"));

  const CliResult r = run(args + " --json resumed.json --checkpoint c.ckpt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("resuming from --checkpoint c.ckpt at t = "), std::string::npos) << r.err;
  EXPECT_EQ(measured(slurp(dir_ / "resumed.json")), measured(slurp(dir_ / "whole.json")));
  EXPECT_FALSE(fs::exists(dir_ / "c.ckpt"));
}

// A run stored already is read back, not run again; a checkpoint of it left behind (its process
// stopped between storing and removing it) is spent and is removed, saying so.
TEST_F(RunCheckpointCli, ASpentCheckpointOfAStoredRunIsRemoved) {
  const std::string args = "run --engine reference --N 3 --T 200 --transient 0 --seed 1 --db r.db -q --checkpoint c.ckpt";
  ASSERT_EQ(run(args).exit_code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "c.ckpt"));
  const RunSpec three = three_particles();
  const std::optional<StateArchive> saved = run_until(three, 50);
  ASSERT_TRUE(saved.has_value());
  write_run_checkpoint((dir_ / "c.ckpt").string(), {point_key(three), "test", *saved});
  const CliResult r = run(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("is this run already"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("held the state of this stored run; it was removed"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "c.ckpt"));
  EXPECT_EQ(query(dir_ / "r.db", "SELECT count(*) FROM runs"), 1);
}
