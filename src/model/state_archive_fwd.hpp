#pragma once
// The saved-state type (model/state_archive.hpp) for headers that only pass it on.
#include <nlohmann/json_fwd.hpp>

namespace granchain {
using StateArchive = nlohmann::json;
}  // namespace granchain
