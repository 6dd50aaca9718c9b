#pragma once
// Contact durations (observables/contact_durations.hpp) summed over a layer of the column: pairs
// first_pair .. last_pair (pair i joins particles i and i + 1; pair 0, a plate's contact, is not a
// layer's). A binary collision of the spring-dashpot law lasts tau_c (Eq. tauc), shorter ones only
// when grazing; a contact longer than ContactDurations::kLongContact tau_c held three or more
// particles together (or was stretched by the floor's kick, for the bottom pair), the "long-lived
// contacts" the paper's Summary expects in the condensed layer near the floor.
#include <cstdint>
#include <vector>

#include "observables/contact_durations.hpp"

namespace granchain::analysis {

inline constexpr double kLongContact = ContactDurations::kLongContact;

struct ContactLayer {
  int first_pair = 0, last_pair = 0;
  std::uint64_t contacts = 0;       // contacts that ended in the window
  double contact_fraction = 0;      // mean over the layer's pairs of the fraction of the window in contact
  double mean_duration = 0;         // mean duration of its contacts / tau_c (0 without contacts)
  double longest = 0;               // the longest / tau_c (an open contact's age included)
  // The share of the layer's time in contact spent in contacts longer than kLongContact tau_c (the
  // contacts still open at the window's end included); 0 without contact, NaN for runs stored before
  // the observer kept that time.
  double long_share = 0;
};

// pairs: index 0 the plate, 1 .. N-1 the particles' pairs (ContactDurations::pairs()). Throws
// std::invalid_argument unless 1 <= first_pair <= last_pair < pairs.size().
ContactLayer contact_layer(const std::vector<PairContacts>& pairs, int first_pair, int last_pair);

// The column cut into `layers` layers of (nearly) equal numbers of pairs, bottom first.
std::vector<ContactLayer> contact_layers(const std::vector<PairContacts>& pairs, int layers);

}  // namespace granchain::analysis
