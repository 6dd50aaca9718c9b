#include "sweep/mpi_sweep.hpp"

#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "store/output_file.hpp"
#include "store/run_json.hpp"

#ifdef GRANCHAIN_WITH_MPI
#include <mpi.h>
#endif

namespace granchain {

bool launched_by_mpi_launcher() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
    const char* v = std::getenv(var);
    if (v && std::atoi(v) > 1) return true;
  }
  return false;
}

#ifdef GRANCHAIN_WITH_MPI

bool built_with_mpi() { return true; }

namespace {

constexpr int kTagReady = 1;  // rank -> 0: JSON {"index", "result" | "error"} of its last point, or {}
constexpr int kTagWork = 2;   // 0 -> rank: one long long, the point's index, or -1 to stop

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

// Waits for a message without spinning a core (MPI's blocking calls busy-poll in OpenMPI).
MPI_Status wait_for(int source, int tag) {
  MPI_Status status;
  int flag = 0;
  for (;;) {
    check(MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status), "Iprobe");
    if (flag) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void serve_ranks(const MpiWorld& world, SweepRunner& runner) {
  int active = world.size() - 1;
  while (active > 0) {
    MPI_Status status = wait_for(MPI_ANY_SOURCE, kTagReady);
    int length = 0;
    check(MPI_Get_count(&status, MPI_CHAR, &length), "Get_count");
    std::string text(static_cast<std::size_t>(length), '\0');
    check(MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "Recv");
    const nlohmann::json message = nlohmann::json::parse(text);
    if (message.contains("index")) {
      const auto index = message.at("index").get<std::size_t>();
      if (message.contains("fatal")) runner.fail(std::make_exception_ptr(OutputError(message.at("fatal").get<std::string>())));
      if (message.contains("saved")) {
        runner.record_saved(index);
      } else if (message.contains("abandoned")) {
        runner.put_back(index);
      } else if (message.contains("result")) {
        const RunResult result = run_result_from_json(message.at("result"));
        runner.record(index, &result, "");
      } else if (message.contains("collapse")) {
        const nlohmann::json& c = message.at("collapse");
        const InelasticCollapseError collapse(c.at("t").get<double>(), c.at("first").get<int>(), c.at("last").get<int>(),
                                              c.at("collisions").get<std::uint64_t>(), message.at("error").get<std::string>());
        runner.record(index, nullptr, collapse.what(), {}, &collapse);
      } else {
        runner.record(index, nullptr, message.at("error").get<std::string>());
      }
    }
    // A rank that was stopped by a signal of its own leaves, whatever rank 0 does.
    const auto next = message.contains("leaving") ? std::nullopt : runner.next();
    long long index = next ? static_cast<long long>(*next) : -1;
    check(MPI_Send(&index, 1, MPI_LONG_LONG, status.MPI_SOURCE, kTagWork, MPI_COMM_WORLD), "Send");
    if (!next) --active;
  }
}

void work_for_rank0(const std::vector<SweepPoint>& points, const SweepCheckpoints* checkpoints, const PointStops& stops) {
  std::string text = cancel_requested(stops.cancel) ? R"({"leaving": true})" : "{}";
  for (;;) {
    check(MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kTagReady, MPI_COMM_WORLD), "Send");
    wait_for(0, kTagWork);
    long long index = -1;
    check(MPI_Recv(&index, 1, MPI_LONG_LONG, 0, kTagWork, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "Recv");
    if (index < 0) return;
    nlohmann::json message = {{"index", index}};
    PointOutcome outcome;
    try {
      outcome = run_sweep_point(points.at(static_cast<std::size_t>(index)), checkpoints, stops);
    } catch (const std::exception& e) {  // a checkpoint that cannot be written: the sweep stops
      message["fatal"] = e.what();
      outcome.end = PointEnd::Abandoned;
    }
    switch (outcome.end) {
      case PointEnd::Finished:
        message["result"] = run_result_to_json(*outcome.result);
        break;
      case PointEnd::Collapsed: {
        const InelasticCollapseError& c = *outcome.collapse;
        message["error"] = outcome.error;
        message["collapse"] = {{"t", c.time()}, {"first", c.particle_a()}, {"last", c.particle_b()}, {"collisions", c.collisions()}};
        break;
      }
      case PointEnd::Failed:
        message["error"] = outcome.error;
        break;
      case PointEnd::Saved:
        message["saved"] = outcome.saved_t;
        break;
      case PointEnd::Abandoned:  // cancelled unsaved: back in rank 0's queue
        message["abandoned"] = true;
        break;
    }
    if (cancel_requested(stops.cancel)) message["leaving"] = true;
    text = message.dump();
  }
}

}  // namespace

MpiWorld::MpiWorld() {
  if (!launched_by_mpi_launcher()) return;
  int provided = 0;
  // Only the main thread of each rank calls MPI (rank 0's worker threads never do).
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "Init_thread");
  initialised_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiWorld::~MpiWorld() {
  if (initialised_) MPI_Finalize();
}

int MpiWorld::broadcast(int x) const {
  if (initialised_) check(MPI_Bcast(&x, 1, MPI_INT, 0, MPI_COMM_WORLD), "Bcast");
  return x;
}

void run_sweep_over_ranks(const MpiWorld& world, const std::vector<SweepPoint>& points, SweepRunner* runner,
                          int threads, const SweepProgressCallback& progress, double progress_every,
                          const SweepCheckpoints* checkpoints, const PointStops& rank_stops) {
  if (world.rank() != 0) {
    work_for_rank0(points, checkpoints, rank_stops);
    return;
  }
  runner->run(threads, progress, progress_every, [&] { serve_ranks(world, *runner); });
}

#else  // no MPI in this build: a one-rank world

bool built_with_mpi() { return false; }
MpiWorld::MpiWorld() = default;
MpiWorld::~MpiWorld() = default;
int MpiWorld::broadcast(int x) const { return x; }
void run_sweep_over_ranks(const MpiWorld&, const std::vector<SweepPoint>&, SweepRunner* runner, int threads,
                          const SweepProgressCallback& progress, double progress_every, const SweepCheckpoints*, const PointStops&) {
  runner->run(threads, progress, progress_every);
}

#endif

}  // namespace granchain
