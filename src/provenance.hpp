#pragma once
// Where a result came from, recorded in every JSON output and every stored run: the command line,
// host, threads and MPI ranks, the build (type, compiler and flags, MPI on/off), the code version
// and the units. The program sets its invocation once; the rest is read here.
#include <nlohmann/json.hpp>
#include <string>

namespace granchain {

// "build type Release; compiler GNU 12.2.0; flags -O3 ...; MPI on", fixed at configure time.
const char* build_settings();

// The command line as typed (arguments quoted where needed), and the parallelism of this process:
// threads running points at once, and MPI ranks (1 without MPI).
void set_invocation(int argc, const char* const* argv);
void set_invocation_text(const std::string& command_line);
void set_parallelism(int threads, int ranks);

// {"command_line", "host", "threads", "ranks", "build", "mpi", "code_version", "units"}.
nlohmann::json provenance_json();

}  // namespace granchain
