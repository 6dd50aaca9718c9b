#include "analysis/contact_layers.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace granchain::analysis {

ContactLayer contact_layer(const std::vector<PairContacts>& pairs, int first_pair, int last_pair) {
  if (first_pair < 1 || last_pair < first_pair || last_pair >= static_cast<int>(pairs.size()))
    throw std::invalid_argument("contact_layer: pairs out of range");
  ContactLayer layer;
  layer.first_pair = first_pair;
  layer.last_pair = last_pair;
  double duration_sum = 0, in_contact = 0, in_long = 0;
  for (int i = first_pair; i <= last_pair; ++i) {
    const PairContacts& p = pairs[static_cast<std::size_t>(i)];
    layer.contacts += p.contacts;
    in_contact += p.contact_fraction;
    in_long += p.long_fraction;
    duration_sum += p.mean * static_cast<double>(p.contacts);
    layer.longest = std::max(layer.longest, p.longest);
  }
  layer.contact_fraction = in_contact / (last_pair - first_pair + 1);
  if (layer.contacts > 0) layer.mean_duration = duration_sum / static_cast<double>(layer.contacts);
  if (std::isnan(in_long)) layer.long_share = std::nan("");  // a run stored before the observer kept it
  else if (in_contact > 0) layer.long_share = in_long / in_contact;
  return layer;
}

std::vector<ContactLayer> contact_layers(const std::vector<PairContacts>& pairs, int layers) {
  const int n = static_cast<int>(pairs.size()) - 1;  // pairs 1 .. n
  if (n < 1 || layers < 1) throw std::invalid_argument("contact_layers: no pairs or no layers");
  layers = std::min(layers, n);
  std::vector<ContactLayer> out;
  for (int l = 0; l < layers; ++l) out.push_back(contact_layer(pairs, 1 + l * n / layers, (l + 1) * n / layers));
  return out;
}

}  // namespace granchain::analysis
