// Contact durations summed over layers of the column (analysis/contact_layers.hpp): the share of
// contact time in contacts longer than 2 tau_c counts a contact still open at the window's end as
// long; a column resting on a cold floor is held together near the floor, a fluid column's
// contacts are binary collisions.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "analysis/contact_layers.hpp"
#include "simulation/driven_run.hpp"

using namespace granchain;
using analysis::contact_layer;
using analysis::contact_layers;

// Pair 1: ten binary collisions (all in the bin of 1 tau_c), 10.5 tau_c in contact; pair 2: one
// contact open through the whole window of 1000 tau_c, in no histogram but long.
TEST(ContactLayers, AContactOpenThroughTheWindowIsLong) {
  std::vector<PairContacts> pairs(3);
  pairs[1].contacts = 10;
  pairs[1].mean = 1.05;
  pairs[1].longest = 1.2;
  pairs[1].contact_fraction = 10.5 / 1000.0;
  pairs[1].first_bin = ContactDurations::bin_of(1.05);
  pairs[1].histogram = {10};
  pairs[2].open_at_end = 1;
  pairs[2].longest = 1000.0;
  pairs[2].contact_fraction = 1.0;
  pairs[2].long_fraction = 1.0;
  ASSERT_EQ(ContactDurations::bin_lower_edge(pairs[1].first_bin), 1.0);
  const analysis::ContactLayer both = contact_layer(pairs, 1, 2);
  EXPECT_EQ(both.contacts, 10u);
  EXPECT_DOUBLE_EQ(both.mean_duration, 1.05);
  EXPECT_DOUBLE_EQ(both.longest, 1000.0);
  EXPECT_DOUBLE_EQ(both.contact_fraction, (10.5 / 1000.0 + 1.0) / 2.0);
  EXPECT_DOUBLE_EQ(both.long_share, 1000.0 / 1010.5);
  EXPECT_EQ(contact_layer(pairs, 1, 1).long_share, 0.0);
  EXPECT_EQ(contact_layer(pairs, 2, 2).long_share, 1.0);
  EXPECT_THROW(contact_layer(pairs, 0, 2), std::invalid_argument);
  EXPECT_THROW(contact_layer(pairs, 1, 3), std::invalid_argument);
  // A run stored before the long-contact time was kept: no share.
  pairs[1].long_fraction = std::nan("");
  EXPECT_TRUE(std::isnan(contact_layer(pairs, 1, 2).long_share));
}

// Nine pairs in three layers: 1-3, 4-6, 7-9, each pair once; more layers than pairs: one each.
TEST(ContactLayers, LayersCoverEveryPairOnce) {
  std::vector<PairContacts> pairs(10);
  const auto three = contact_layers(pairs, 3);
  ASSERT_EQ(three.size(), 3u);
  EXPECT_EQ(three[0].first_pair, 1);
  EXPECT_EQ(three[0].last_pair, 3);
  EXPECT_EQ(three[1].first_pair, 4);
  EXPECT_EQ(three[2].last_pair, 9);
  const auto many = contact_layers(pairs, 20);
  ASSERT_EQ(many.size(), 9u);
  for (int l = 0; l < 9; ++l) EXPECT_EQ(many[static_cast<std::size_t>(l)].first_pair, l + 1);
}

// A column of N = 10 at e = 0.1 on a cold floor (k_B T0 = 1e-4, far below its weight m g d) rests:
// its bottom tenth spends its contact time in one held contact. The paper's fluid column (k_B T0 = 1,
// e = 0.95) collides in binary collisions: little of its contact time is in contacts longer than
// 2 tau_c, and its mean contact lasts about tau_c.
TEST(ContactLayers, ARestingColumnIsHeldAndAFluidOneCollides) {
  const auto column = [](double e, double kT0) {
    RunSpec spec;
    spec.params = ChainParameters{.N = 10, .k = 1e4, .e = e, .kT0 = kT0};
    spec.T = 50.0;
    spec.transient = 20.0;
    return run_driven_column(spec);
  };
  const RunResult rest = column(0.1, 1e-4);
  const auto rest_layers = contact_layers(rest.contacts, 10);
  EXPECT_GT(rest_layers.front().contact_fraction, 0.99);
  EXPECT_GT(rest_layers.front().long_share, 0.99);

  const RunResult fluid = column(0.95, 1.0);
  const analysis::ContactLayer whole = contact_layer(fluid.contacts, 1, 9);
  EXPECT_GT(whole.contacts, 500u);
  EXPECT_NEAR(whole.mean_duration, 1.0, 0.1);
  EXPECT_LT(whole.long_share, 0.1);
}
