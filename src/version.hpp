#pragma once

namespace granchain {
// "<project version>+g<git describe>", fixed at build time; stored with every run.
const char* code_version();
}  // namespace granchain
