#pragma once
// Joining results stores (job-array shards, runs made on several machines) into one.
#include <cstdint>
#include <string>
#include <vector>

#include "store/results_store.hpp"

namespace granchain {

// Two stores hold one point (the same key, or for collapse counts the same parameters and seed)
// with different results: the code or the machine changed something it should not have.
class MergeConflict : public StoreError {
 public:
  using StoreError::StoreError;
};

// Writing the target failed (a full disk, an I/O error): not bad input; nothing was merged.
class MergeWriteError : public StoreError {
 public:
  using StoreError::StoreError;
};

struct MergeReport {
  std::int64_t runs_added = 0;
  std::int64_t runs_already_there = 0;      // identical point already in the target
  std::int64_t collapse_added = 0;
  std::int64_t collapse_already_there = 0;
  std::int64_t collapsed_added = 0;           // hard-sphere sweep points that collapsed (collapsed_points)
  std::int64_t collapsed_already_there = 0;
  std::int64_t launches_added = 0;           // kept launches of counts not yet whole (collapse_launches)
  std::int64_t launches_already_there = 0;
};

// Copies every run (with its profiles and key), every collapse count (with its realisations),
// every collapsed hard-sphere point and every kept launch of an unfinished count (dropping those
// of counts the target then holds whole) of the sources into target, which is created if missing. A point present in both with the same
// results is kept once; with different results the merge throws MergeConflict naming both and
// the differing numbers; a failure to write the target throws MergeWriteError. All sources go in
// one transaction: on any error nothing is written.
// Sources are only read.
MergeReport merge_stores(const std::string& target, const std::vector<std::string>& sources);

}  // namespace granchain
