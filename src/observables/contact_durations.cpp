#include "observables/contact_durations.hpp"

#include <algorithm>

#include "model/state_archive.hpp"
#include <bit>
#include <cmath>
#include <limits>

namespace granchain {

double ContactDurations::bin_lower_edge(int b) { return std::exp2(kLog2Min + static_cast<double>(b) / kBinsPerOctave); }

int ContactDurations::bin_of(double x) {
  if (!(x >= 0x1p-1022) || !std::isfinite(x)) return x > 1 ? kBins - 1 : 0;  // subnormal, zero, negative, NaN; infinity
  // x = f 2^q with 1 <= f < 2, read from the bits (no library call per contact); quarter octaves at
  // 2^(1/4), 2^(1/2), 2^(3/4).
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const int q = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  const double f = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  const int quarter = (f >= 1.189207115002721) + (f >= 1.4142135623730951) + (f >= 1.6817928305074290);
  return std::clamp((q - kLog2Min) * kBinsPerOctave + quarter, 0, kBins - 1);
}

ContactDurations::ContactDurations(int N, double tau_c, double t_begin, double t_end)
    : n_(N),
      tau_c_(tau_c),
      inverse_tau_c_(1.0 / tau_c),
      t_begin_(t_begin),
      t_end_(t_end),
      begin_hi_(static_cast<std::size_t>(N), std::numeric_limits<double>::quiet_NaN()),
      begin_lo_(static_cast<std::size_t>(N), 0.0),
      count_(static_cast<std::size_t>(N), 0),
      before_(static_cast<std::size_t>(N), 0),
      sum_(static_cast<std::size_t>(N), 0.0),
      longest_(static_cast<std::size_t>(N), 0.0),
      in_window_(static_cast<std::size_t>(N), 0.0),
      long_in_window_(static_cast<std::size_t>(N), 0.0),
      hist_(static_cast<std::size_t>(N) * kBins, 0) {}

void ContactDurations::on_event(const Event& ev) {
  // Slot 0: the plate's contact with particle 1; slot i + 1: pair (i, i + 1).
  int slot = -1;
  bool begins = false;
  switch (ev.kind) {
    case EventKind::ContactBegin: slot = ev.i + 1, begins = true; break;
    case EventKind::ContactEnd: slot = ev.i + 1; break;
    case EventKind::FloorContact: slot = 0, begins = true; break;
    case EventKind::FloorHit: slot = 0; break;
  }
  if (slot < 0 || slot >= n_) return;
  const auto s = static_cast<std::size_t>(slot);
  if (begins) {
    begin_hi_[s] = ev.t;
    begin_lo_[s] = ev.t_low;
    return;
  }
  if (std::isnan(begin_hi_[s])) return;  // a thermal floor's hit, or an end whose begin came before the first event seen
  if (ev.t >= t_end_) return;  // ends at or after the window's end (round-off at t_end): open at the end, as pairs() counts it
  const double b = begin_hi_[s];
  // (t + t_low) - (b + b_low), the large parts first: exact for a contact short beside t.
  const double duration = (ev.t - b) + (ev.t_low - begin_lo_[s]);
  begin_hi_[s] = std::numeric_limits<double>::quiet_NaN();
  if (ev.t < t_begin_) return;
  const double part = ev.t - std::max(b, t_begin_);
  in_window_[s] += part;
  if (duration * inverse_tau_c_ > kLongContact) long_in_window_[s] += part;
  finish(slot, duration, b < t_begin_);
}

void ContactDurations::finish(int slot, double duration, bool began_before) {
  const auto s = static_cast<std::size_t>(slot);
  const double x = duration * inverse_tau_c_;
  ++count_[s];
  if (began_before) ++before_[s];
  sum_[s] += x;
  longest_[s] = std::max(longest_[s], x);
  ++hist_[s * kBins + static_cast<std::size_t>(bin_of(x))];
}

std::vector<PairContacts> ContactDurations::pairs() const {
  std::vector<PairContacts> out(static_cast<std::size_t>(n_));
  const double T = t_end_ - t_begin_;
  for (std::size_t s = 0; s < out.size(); ++s) {
    PairContacts& p = out[s];
    p.contacts = count_[s];
    p.began_before = before_[s];
    p.mean = count_[s] ? sum_[s] / static_cast<double>(count_[s]) : 0.0;
    p.longest = longest_[s];
    double in_window = in_window_[s], long_in_window = long_in_window_[s];
    if (!std::isnan(begin_hi_[s]) && begin_hi_[s] < t_end_) {  // open at the window's end
      p.open_at_end = 1;
      const double part = t_end_ - std::max(begin_hi_[s], t_begin_), age = (t_end_ - begin_hi_[s]) / tau_c_;
      in_window += part;
      if (age > kLongContact) long_in_window += part;
      p.longest = std::max(p.longest, age);
    }
    p.contact_fraction = T > 0 ? in_window / T : 0.0;
    p.long_fraction = T > 0 ? long_in_window / T : 0.0;
    const auto h_begin = hist_.begin() + static_cast<std::ptrdiff_t>(s * kBins), h_end = h_begin + kBins;
    const auto first = std::find_if(h_begin, h_end, [](std::uint64_t c) { return c > 0; });
    if (first == h_end) continue;
    const auto last = std::find_if(std::make_reverse_iterator(h_end), std::make_reverse_iterator(h_begin), [](std::uint64_t c) { return c > 0; }).base();
    p.first_bin = static_cast<int>(first - h_begin);
    p.histogram.assign(first, last);
  }
  return out;
}

void ContactDurations::save(StateArchive& out) const {
  out["begin_hi"] = pack_array(begin_hi_);
  out["begin_lo"] = pack_array(begin_lo_);
  out["count"] = pack_array(count_);
  out["before"] = pack_array(before_);
  out["sum"] = pack_array(sum_);
  out["longest"] = pack_array(longest_);
  out["in_window"] = pack_array(in_window_);
  out["long_in_window"] = pack_array(long_in_window_);
  out["histogram"] = pack_array(hist_);
}

void ContactDurations::restore(const StateArchive& in) {
  const auto n = static_cast<std::size_t>(n_);
  begin_hi_ = unpack_array<double>(in, "begin_hi", n);
  begin_lo_ = unpack_array<double>(in, "begin_lo", n);
  count_ = unpack_array<std::uint64_t>(in, "count", n);
  before_ = unpack_array<std::uint64_t>(in, "before", n);
  sum_ = unpack_array<double>(in, "sum", n);
  longest_ = unpack_array<double>(in, "longest", n);
  in_window_ = unpack_array<double>(in, "in_window", n);
  long_in_window_ = unpack_array<double>(in, "long_in_window", n);
  hist_ = unpack_array<std::uint64_t>(in, "histogram", n * kBins);
}

}  // namespace granchain
