#pragma once
// "Did you mean ...?" for a mistyped subcommand or flag: the nearest valid name by edit distance.
#include <string>
#include <vector>

namespace granchain {

// Levenshtein distance (insertions, deletions, substitutions; a swap of neighbours counts 1).
std::size_t edit_distance(const std::string& a, const std::string& b);

// The candidate nearest to `word`, if within max(1, size/3) edits (ties: the first); else "".
std::string nearest_name(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace granchain
