#include "analysis/contact_layers.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace granchain::analysis {

ContactLayer contact_layer(const std::vector<PairContacts>& pairs, int first_pair, int last_pair, double window) {
  if (first_pair < 1 || last_pair < first_pair || last_pair >= static_cast<int>(pairs.size()))
    throw std::invalid_argument("contact_layer: pairs out of range");
  if (!(window > 0)) throw std::invalid_argument("contact_layer: the window must be > 0");
  ContactLayer layer;
  layer.first_pair = first_pair;
  layer.last_pair = last_pair;
  double duration_sum = 0, in_contact = 0, short_time = 0;
  const double half_bin = std::exp2(0.5 / ContactDurations::kBinsPerOctave);
  for (int i = first_pair; i <= last_pair; ++i) {
    const PairContacts& p = pairs[static_cast<std::size_t>(i)];
    layer.contacts += p.contacts;
    layer.contact_fraction += p.contact_fraction;
    in_contact += p.contact_fraction * window;
    duration_sum += p.mean * static_cast<double>(p.contacts);
    layer.longest = std::max(layer.longest, p.longest);
    for (std::size_t j = 0; j < p.histogram.size(); ++j) {
      const int bin = p.first_bin + static_cast<int>(j);
      const double lower = ContactDurations::bin_lower_edge(bin);
      if (lower < kLongContact) short_time += static_cast<double>(p.histogram[j]) * lower * half_bin;
    }
  }
  layer.contact_fraction /= last_pair - first_pair + 1;
  if (layer.contacts > 0) layer.mean_duration = duration_sum / static_cast<double>(layer.contacts);
  if (in_contact > 0) layer.long_share = std::clamp(1.0 - short_time / in_contact, 0.0, 1.0);
  return layer;
}

std::vector<ContactLayer> contact_layers(const std::vector<PairContacts>& pairs, int layers, double window) {
  const int n = static_cast<int>(pairs.size()) - 1;  // pairs 1 .. n
  if (n < 1 || layers < 1) throw std::invalid_argument("contact_layers: no pairs or no layers");
  layers = std::min(layers, n);
  std::vector<ContactLayer> out;
  for (int l = 0; l < layers; ++l) out.push_back(contact_layer(pairs, 1 + l * n / layers, (l + 1) * n / layers, window));
  return out;
}

}  // namespace granchain::analysis
