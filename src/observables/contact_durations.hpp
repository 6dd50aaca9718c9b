#pragma once
// How long neighbours stay in contact. A binary collision of the spring-dashpot law lasts tau_c
// (Eq. tauc); in a condensed layer, the paper's Summary warns, "the contacts among them cannot be
// resolved into binary collisions but may remain as long-lived contacts". Per pair (i, i+1), from
// its ContactBegin to its ContactEnd, in units of tau_c: a histogram in log2(duration / tau_c),
// the contacts' number, mean and longest duration, and the fraction of the window the pair spends in
// contact. A vibrating plate's contact with particle 1 (FloorContact to FloorHit) is pair 0; the
// thermal floor's hits are instantaneous and have none.
#include <cstdint>
#include <vector>

#include "engines/events.hpp"
#include "model/state_archive_fwd.hpp"

namespace granchain {

struct PairContacts {
  std::uint64_t contacts = 0;        // contacts that ended in the window
  std::uint64_t began_before = 0;    // of those, begun before the window (their whole duration counts)
  std::uint64_t open_at_end = 0;     // 0 or 1: a contact still open when the window ends (not in the histogram)
  double mean = 0.0;                 // mean duration / tau_c of the contacts that ended in the window
  double longest = 0.0;              // the longest of them / tau_c (an open one: its age at the end, if longer)
  double contact_fraction = 0.0;     // time in contact within the window / T
  // Of that, the time in contacts longer than ContactDurations::kLongContact tau_c (an open one:
  // once its age exceeds it) / T. NaN in runs stored before it was kept.
  double long_fraction = 0.0;
  int first_bin = 0;                 // histogram[j] counts durations in bin first_bin + j
  std::vector<std::uint64_t> histogram;
};

class ContactDurations final : public EventSink {
 public:
  // Bins of log2(duration / tau_c): kBinsPerOctave per factor 2 from 2^kLog2Min; shorter durations
  // go to the first bin, longer ones to the last. (Powers of 2: the bin comes from the binary
  // exponent and three comparisons, no logarithm per contact.)
  static constexpr int kBinsPerOctave = 4;
  static constexpr int kLog2Min = -8;  // 0.004 tau_c
  static constexpr int kBins = 4 * 72;  // up to 2^64 = 1.8e19 tau_c
  // A binary collision of the spring-dashpot law lasts exactly tau_c (a grazing one less); a contact
  // longer than twice that held three or more particles together (or, for the bottom pair, was
  // stretched by a kick of the floor).
  static constexpr double kLongContact = 2.0;
  // Lower edge of bin b in units of tau_c: 2^(kLog2Min + b / kBinsPerOctave).
  static double bin_lower_edge(int b);
  // The bin of a duration x (in units of tau_c).
  static int bin_of(double x);

  // N particles; events of any time may arrive (the transient too): a contact counts when it ends in
  // [t_begin, t_end).
  ContactDurations(int N, double tau_c, double t_begin, double t_end);
  void on_event(const Event& event) override;
  // Pair 0 (the plate) and pairs 1 .. N-1, with the contacts open at t_end counted and aged.
  std::vector<PairContacts> pairs() const;
  // The open contacts and the durations so far, for a run's checkpoint (model/state_archive.hpp).
  void save(StateArchive& out) const;
  void restore(const StateArchive& in);

 private:
  void finish(int slot, double duration, bool began_before);
  int n_;
  double tau_c_, inverse_tau_c_, t_begin_, t_end_;
  std::vector<double> begin_hi_, begin_lo_;  // open contact's begin time (t + t_low), NaN when closed
  std::vector<std::uint64_t> count_, before_;
  std::vector<double> sum_, longest_, in_window_, long_in_window_;
  std::vector<std::uint64_t> hist_;  // pair-major: hist_[slot * kBins + bin]
};

}  // namespace granchain
