// How long contacts last (observables/contact_durations.hpp): a binary collision of the
// spring-dashpot law lasts exactly tau_c (Eq. tauc), at any k the exact engine's clock resolves; a
// column resting on the floor keeps its bottom contacts closed; the window's bookkeeping of contacts
// that straddle its ends; the durations travel with a run's JSON.
#include <gtest/gtest.h>

#include <cmath>

#include "engines/exact/exact_engine.hpp"
#include "model/chain_parameters.hpp"
#include "observables/contact_durations.hpp"
#include "simulation/driven_run.hpp"
#include "store/run_json.hpp"

using namespace granchain;

namespace {

// Two spheres in free space approach at relative speed 1 from a gap of 0.1 (the clock then reads
// about t0), collide once, and part.
PairContacts binary_collision(double k, double t0) {
  const ChainParameters p{.N = 2, .g = 0.0, .k = k, .e = 0.6};
  ExactEngine engine(p, {t0, {0.0, 1.1}, {0.5, -0.5}}, nullptr);
  ContactDurations contacts(2, contact_law(p).tau_c, t0, t0 + 10.0);
  engine.advance_to(t0 + 1.0, contacts);
  return contacts.pairs().at(1);
}

}  // namespace

TEST(ContactDurations, ABinaryCollisionLastsTauC) {
  for (const double k : {1e4, 1e10, 1e20}) {
    for (const double t0 : {0.0, 1e3}) {
      const PairContacts c = binary_collision(k, t0);
      ASSERT_EQ(c.contacts, 1u) << "k = " << k << ", t0 = " << t0;
      // At t0 = 1e3 and k = 1e20 (tau_c = 3e-10) a double clock resolves tau_c to 1e-3; the
      // exact engine's FineTime, which the events carry, to better than 1e-9.
      EXPECT_NEAR(c.mean, 1.0, 1e-9) << "k = " << k << ", t0 = " << t0;
      EXPECT_EQ(c.longest, c.mean);
      // log2(1) = 0 lies in bin -kLog2Min * kBinsPerOctave.
      EXPECT_EQ(c.first_bin, -ContactDurations::kLog2Min * ContactDurations::kBinsPerOctave);
      ASSERT_EQ(c.histogram.size(), 1u);
      EXPECT_EQ(c.long_fraction, 0.0);  // a binary collision is not a long contact
      EXPECT_NEAR(c.contact_fraction, contact_law(ChainParameters{.N = 2, .g = 0.0, .k = k, .e = 0.6}).tau_c / 10.0, 1e-12);
    }
  }
}

// A contact begun before the window counts whole when it ends inside; one still open at the end is
// counted open, aged to the end, outside the histogram; the time in contact is the window's part.
TEST(ContactDurations, ContactsStraddlingTheWindowAreCountedOnce) {
  ContactDurations c(3, 0.5, 1.0, 10.0);
  const auto ev = [](EventKind kind, double t, int i, double t_low = 0.0) { return Event{kind, t, i, 1.0, t_low}; };
  c.on_event(ev(EventKind::ContactBegin, 0.5, 0));  // pair 1: 0.5 .. 1.5, began before the window
  c.on_event(ev(EventKind::ContactEnd, 1.5, 0));
  c.on_event(ev(EventKind::ContactBegin, 0.2, 1));  // pair 2: 0.2 .. 0.7, entirely before: not counted
  c.on_event(ev(EventKind::ContactEnd, 0.7, 1));
  c.on_event(ev(EventKind::ContactBegin, 9.0, 1));  // pair 2: open from 9.0 at the end
  c.on_event(ev(EventKind::FloorHit, 5.0, 0));       // a thermal floor's hit: no contact
  c.on_event(ev(EventKind::ContactBegin, 4.0, 0, 1e-17));  // pair 1: 4 + 1e-17 .. 4 + 4e-17 (FineTime parts)
  c.on_event(ev(EventKind::ContactEnd, 4.0, 0, 4e-17));
  const auto pairs = c.pairs();
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0].contacts, 0u);
  EXPECT_EQ(pairs[1].contacts, 2u);
  EXPECT_EQ(pairs[1].began_before, 1u);
  EXPECT_DOUBLE_EQ(pairs[1].longest, 2.0);                 // 1.0 / tau_c
  EXPECT_DOUBLE_EQ(pairs[1].mean, (2.0 + 6e-17) / 2);       // (2 + 3e-17 / 0.5) / 2
  EXPECT_DOUBLE_EQ(pairs[1].contact_fraction, 0.5 / 9.0);  // 1.0 .. 1.5 (the 3e-17 are below a double at t = 4)
  EXPECT_EQ(pairs[2].contacts, 0u);
  EXPECT_EQ(pairs[2].open_at_end, 1u);
  EXPECT_DOUBLE_EQ(pairs[2].longest, 2.0);                 // aged 1.0 at t = 10
  EXPECT_DOUBLE_EQ(pairs[2].contact_fraction, 1.0 / 9.0);
  EXPECT_TRUE(pairs[2].histogram.empty());
}

// The time in contacts longer than 2 tau_c (tau_c = 0.5, window 1 .. 10): a long contact begun
// before the window counts its part inside; a short one none; a long one open at the end its part
// inside, a young one open at the end none; a plate's contact likewise.
TEST(ContactDurations, TheTimeInLongContactsIsTheirPartOfTheWindow) {
  ContactDurations c(3, 0.5, 1.0, 10.0);
  const auto ev = [](EventKind kind, double t, int i) { return Event{kind, t, i, 1.0, 0.0}; };
  c.on_event(ev(EventKind::ContactBegin, 0.0, 0));  // pair 1: 0 .. 2, 4 tau_c, 1.0 inside
  c.on_event(ev(EventKind::ContactEnd, 2.0, 0));
  c.on_event(ev(EventKind::ContactBegin, 3.0, 0));  // pair 1: 3 .. 3.4, 0.8 tau_c
  c.on_event(ev(EventKind::ContactEnd, 3.4, 0));
  c.on_event(ev(EventKind::ContactBegin, 5.0, 1));  // pair 2: 5 .. 6.5, 3 tau_c
  c.on_event(ev(EventKind::ContactEnd, 6.5, 1));
  c.on_event(ev(EventKind::ContactBegin, 9.8, 1));  // pair 2: open at the end, aged 0.4 tau_c
  c.on_event(ev(EventKind::FloorContact, 8.0, 0));  // the plate: open at the end, aged 4 tau_c
  const auto pairs = c.pairs();
  EXPECT_DOUBLE_EQ(pairs[1].contact_fraction, 1.4 / 9.0);
  EXPECT_DOUBLE_EQ(pairs[1].long_fraction, 1.0 / 9.0);
  EXPECT_DOUBLE_EQ(pairs[2].contact_fraction, 1.7 / 9.0);
  EXPECT_DOUBLE_EQ(pairs[2].long_fraction, 1.5 / 9.0);
  EXPECT_DOUBLE_EQ(pairs[0].contact_fraction, 2.0 / 9.0);
  EXPECT_DOUBLE_EQ(pairs[0].long_fraction, 2.0 / 9.0);
}

// A column of N = 10 at e = 0.1 on a cold floor (k_B T0 = 1e-4, far below the column's weight m g d)
// rests: its bottom pair stays in contact through the window, while a contact in the paper's fluid
// column (k_B T0 = 1, e = 0.95) lasts about tau_c. Hard spheres have no durations.
TEST(ContactDurations, ARestingColumnKeepsItsBottomContactClosed) {
  RunSpec spec;
  spec.params = ChainParameters{.N = 10, .k = 1e4, .e = 0.1, .kT0 = 1e-4};
  spec.T = 50.0;
  spec.transient = 20.0;
  const RunResult rest = run_driven_column(spec);
  ASSERT_EQ(rest.contacts.size(), 10u);
  EXPECT_GT(rest.contacts[1].contact_fraction, 0.99);
  EXPECT_GT(rest.contacts[1].longest, 0.99 * spec.T / rest.law.tau_c);
  EXPECT_DOUBLE_EQ(rest.contacts[1].long_fraction, rest.contacts[1].contact_fraction);  // one contact, held throughout

  spec.params = ChainParameters{.N = 10, .k = 1e4, .e = 0.95, .kT0 = 1.0};
  const RunResult fluid = run_driven_column(spec);
  for (int i = 1; i < 10; ++i) {
    if (fluid.contacts[static_cast<std::size_t>(i)].contacts < 20) continue;
    EXPECT_NEAR(fluid.contacts[static_cast<std::size_t>(i)].mean, 1.0, 0.2) << "pair " << i;
    EXPECT_LT(fluid.contacts[static_cast<std::size_t>(i)].contact_fraction, 0.2) << "pair " << i;
  }
  // The durations travel with the run's JSON (and so with the store).
  const RunResult back = run_result_from_json(run_result_to_json(fluid));
  ASSERT_EQ(back.contacts.size(), fluid.contacts.size());
  for (std::size_t i = 0; i < back.contacts.size(); ++i) {
    EXPECT_EQ(back.contacts[i].contacts, fluid.contacts[i].contacts);
    EXPECT_EQ(back.contacts[i].histogram, fluid.contacts[i].histogram);
    EXPECT_DOUBLE_EQ(back.contacts[i].mean, fluid.contacts[i].mean);
    EXPECT_DOUBLE_EQ(back.contacts[i].contact_fraction, fluid.contacts[i].contact_fraction);
    EXPECT_DOUBLE_EQ(back.contacts[i].long_fraction, fluid.contacts[i].long_fraction);
  }
  // A run stored before the long-contact time was kept reads back without it (NaN), the rest intact.
  nlohmann::json old = run_result_to_json(fluid);
  for (auto& q : old["contacts"]["pairs"]) q.erase("long_fraction");
  const RunResult before = run_result_from_json(old);
  EXPECT_TRUE(std::isnan(before.contacts[1].long_fraction));
  EXPECT_DOUBLE_EQ(before.contacts[1].contact_fraction, fluid.contacts[1].contact_fraction);
  spec.engine.kind = EngineKind::Hard;
  EXPECT_TRUE(run_driven_column(spec).contacts.empty());
}

// The bins are quarter octaves: each duration lands in the bin whose edges enclose it.
TEST(ContactDurations, EachDurationLandsBetweenItsBinsEdges) {
  for (double x = 0.01; x < 1e18; x *= 1.0371) {
    const int b = ContactDurations::bin_of(x);
    EXPECT_LE(ContactDurations::bin_lower_edge(b), x * (1 + 1e-15)) << x;
    EXPECT_GT(ContactDurations::bin_lower_edge(b + 1), x * (1 - 1e-15)) << x;
  }
  EXPECT_EQ(ContactDurations::bin_of(1e-30), 0);
  EXPECT_EQ(ContactDurations::bin_of(1e30), ContactDurations::kBins - 1);
}
