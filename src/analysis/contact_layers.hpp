#pragma once
// Contact durations (observables/contact_durations.hpp) summed over a layer of the column: pairs
// first_pair .. last_pair (pair i joins particles i and i + 1; pair 0, a plate's contact, is not a
// layer's). A binary collision of the spring-dashpot law lasts tau_c (Eq. tauc), shorter ones only
// when grazing; a contact longer than kLongContact tau_c held three or more particles together, the
// "long-lived contacts" the paper's Summary expects in the condensed layer near the floor.
#include <cstdint>
#include <vector>

#include "observables/contact_durations.hpp"

namespace granchain::analysis {

inline constexpr double kLongContact = 2.0;  // in tau_c: longer than any binary collision

struct ContactLayer {
  int first_pair = 0, last_pair = 0;
  std::uint64_t contacts = 0;       // contacts that ended in the window
  double contact_fraction = 0;      // mean over the layer's pairs of the fraction of the window in contact
  double mean_duration = 0;         // mean duration of its contacts / tau_c (0 without contacts)
  double longest = 0;               // the longest / tau_c (an open contact's age included)
  // The share of the layer's time in contact (within the window) spent in contacts longer than
  // kLongContact tau_c: one minus the time of the shorter ones, from the histograms with each bin's
  // contacts at its geometric centre (bins are a quarter octave wide: off by at most 2^(1/8) - 1 =
  // 9 % of that time), over the time in contact (contact_fraction times the window, exact; it holds
  // the contacts still open at the window's end, which no histogram does). 0 without contact.
  double long_share = 0;
};

// pairs: index 0 the plate, 1 .. N-1 the particles' pairs (ContactDurations::pairs()); window: the
// measuring window T in units of tau_c. Throws std::invalid_argument unless 1 <= first_pair <=
// last_pair < pairs.size() and window > 0.
ContactLayer contact_layer(const std::vector<PairContacts>& pairs, int first_pair, int last_pair, double window);

// The column cut into `layers` layers of (nearly) equal numbers of pairs, bottom first.
std::vector<ContactLayer> contact_layers(const std::vector<PairContacts>& pairs, int layers, double window);

}  // namespace granchain::analysis
