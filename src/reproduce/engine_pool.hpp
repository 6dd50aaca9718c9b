#pragma once
// Engines analysed as one (`analyze --pool-engines`). Engines that integrate the same model agree
// within their errors where that has been checked (docs/engines.md); pooling them lets a column
// measured with one engine join the across-N fits of columns measured with another. Runs of the
// pooled engines form one family per (drive, N, kT0): a point holding runs of several of them is
// their weighted mean, and the replicas' scatter there (the analysis's chi2 against blocking) tests
// their agreement. The family carries the first member's kind and prints as "exact+reference".
#include <algorithm>
#include <string>
#include <vector>

#include "engines/engine_registry.hpp"

namespace granchain {

struct EnginePool {
  std::vector<EngineKind> members;  // empty: every engine analysed apart

  bool pools(EngineKind k) const { return std::find(members.begin(), members.end(), k) != members.end(); }
  // The engine a run of kind k is analysed under.
  EngineKind family_engine(EngineKind k) const { return pools(k) ? members.front() : k; }
  // How a family of that engine is named in the analysis's text, JSON and file names.
  std::string label(EngineKind k) const {
    if (!pools(k)) return engine_name(k);
    std::string out;
    for (EngineKind m : members) out += (out.empty() ? "" : "+") + std::string(engine_name(m));
    return out;
  }
};

}  // namespace granchain
