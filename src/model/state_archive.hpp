#pragma once
// A run's saved state (a checkpoint), from which it continues bit for bit: each part of a run
// (engine, floor, observers) writes its own fields into one JSON object, kept on disk as CBOR
// (store/run_checkpoint.hpp). Scalars are JSON numbers (doubles exactly: CBOR keeps them whole);
// arrays go in as the raw bytes of this machine's numbers, so a checkpoint is read back on a
// machine of the same byte order (the cluster that wrote it), and each array's length is checked.
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "model/state_archive_fwd.hpp"

namespace granchain {

// A saved state that does not fit the run that reads it (another N, a truncated file).
class StateArchiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <class T>
nlohmann::json::binary_t pack_array(const std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
  if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return nlohmann::json::binary_t(std::move(bytes));
}

// The array saved under `key` of `in`, which must hold `expected` values.
template <class T>
std::vector<T> unpack_array(const StateArchive& in, const char* key, std::size_t expected) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (!in.contains(key) || !in.at(key).is_binary()) throw StateArchiveError(std::string("saved state: no array '") + key + "'");
  const auto& bytes = in.at(key).get_binary();
  if (bytes.size() != expected * sizeof(T)) {
    throw StateArchiveError(std::string("saved state: array '") + key + "' holds " + std::to_string(bytes.size() / sizeof(T)) +
                            " values, this run has " + std::to_string(expected));
  }
  std::vector<T> values(expected);
  if (!bytes.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

// The number saved under `key` (a missing or mistyped field is a StateArchiveError).
template <class T>
T saved_value(const StateArchive& in, const char* key) {
  if (!in.contains(key)) throw StateArchiveError(std::string("saved state: no field '") + key + "'");
  try {
    return in.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw StateArchiveError(std::string("saved state: field '") + key + "' has the wrong type");
  }
}

}  // namespace granchain
