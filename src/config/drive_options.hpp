#pragma once
// The drive's entries of the driven column's parameter table (model/plate_motion.hpp): which drive,
// the plate's amplitude A and angular frequency omega (part of a run's identity where a plate
// drives), and Gamma and f, which give them another way.
#include <map>
#include <string>
#include <vector>

#include "config/run_definition.hpp"

namespace granchain::run_table {

void add_drive_definitions(std::vector<Definition>& table);

// After every raw value is read: A from Gamma (A = Gamma g / (gamma_factor omega^2)), omega from f
// (omega = 2 pi f); a plate needs one of A, Gamma and one of omega, f, the thermal floor takes none
// of them, and the engine must run plates. InputError naming the parameter otherwise.
void resolve_drive(RunOptions& o, const std::map<std::string, RawValue>& raw);

}  // namespace granchain::run_table
