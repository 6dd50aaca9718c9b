// The exact engine's checkpoint (Engine::save / restore): everything its future depends on, kept
// as it is stored, never recomputed: the clusters (extent, formation time, centre-of-mass velocity,
// modes at formation and their bounds), each open gap and the floor height as a value at its own
// reference time with the edges' mode parts there, the schedule (every slot's time and event), the
// vibrating plate's piece and grounded cluster, the mode cache (a recomputed mode may differ from a
// cached one in its last bit) and the counts. FineTimes are kept whole (both of their doubles).
#include <cmath>
#include <cstring>
#include <type_traits>

#include "engines/exact/exact_engine.hpp"
#include "model/state_archive.hpp"

namespace granchain {

namespace {

void put_time(StateArchive& out, const char* key, const FineTime& t) { out[key] = pack_array(std::vector<FineTime>{t}); }
FineTime saved_time(const StateArchive& in, const char* key) { return unpack_array<FineTime>(in, key, 1)[0]; }

// The archive's layout: the fields below, SlotKind's numbering and ExactCounters' order (saved as
// raw numbers). Raise it when any of them changes, so that a state of another layout is refused.
constexpr int kLayout = 1;

// ExactCounters is a row of 64-bit counts.
constexpr std::size_t kCounts = sizeof(ExactCounters) / sizeof(std::uint64_t);
static_assert(sizeof(ExactCounters) == kCounts * sizeof(std::uint64_t) && std::is_trivially_copyable_v<ExactCounters>);

}  // namespace

void ExactEngine::save(StateArchive& out) const {
  out["layout"] = kLayout;
  put_time(out, "now", now_);
  out["hi"] = pack_array(hi_);
  out["lo_of"] = pack_array(lo_of_);
  out["t0"] = pack_array(t0_);
  out["V0"] = pack_array(V0_);
  out["search_from"] = pack_array(search_from_);
  out["grazing_streak"] = pack_array(grazing_streak_);
  out["hold_until"] = pack_array(hold_until_);
  out["generation"] = pack_array(generation_);
  out["formations"] = formations_;
  out["y0"] = pack_array(y0_);
  out["yd0"] = pack_array(yd0_);
  out["amp0"] = pack_array(amp0_);
  out["gap_t"] = pack_array(gaps_.t);
  out["gap_s"] = pack_array(gaps_.s);
  out["gap_c"] = pack_array(gaps_.c);
  out["gap_ma"] = pack_array(gap_ma_);
  out["gap_mb"] = pack_array(gap_mb_);
  put_time(out, "floor_t", floor_t_);
  out["floor_s"] = floor_s_;
  out["floor_u"] = floor_u_;

  const int slots = schedule_.slots();
  std::vector<std::uint8_t> kind(slots);
  std::vector<int> pair(slots);
  std::vector<double> tau(slots);
  for (int s = 0; s < slots; ++s) {
    const SlotDetail& d = schedule_.detail(s);
    kind[s] = static_cast<std::uint8_t>(d.kind);
    pair[s] = d.pair;
    tau[s] = d.tau;
  }
  out["slot_time"] = pack_array(schedule_.times());
  out["slot_kind"] = pack_array(kind);
  out["slot_pair"] = pack_array(pair);
  out["slot_tau"] = pack_array(tau);

  std::vector<std::uint64_t> counts(kCounts);
  std::memcpy(counts.data(), static_cast<const void*>(&counters_), sizeof(ExactCounters));
  out["counts"] = pack_array(counts);
  out["shortcut_events"] = shortcut_events_;
  out["audit_draws"] = audit_draws_;

  out["cache_lo"] = cache_.lo;
  out["cache_generation"] = cache_.generation;
  put_time(out, "cache_t", cache_.t);
  out["cache_y"] = pack_array(cache_.y);
  out["cache_yd"] = pack_array(cache_.yd);

  if (plate_ != nullptr) {
    put_time(out, "piece_t0", piece_.t0);
    put_time(out, "piece_end", piece_.end);
    out["piece_zva"] = pack_array(std::vector<double>{piece_.z, piece_.v, piece_.a});
    out["grounded"] = grounded_;
    out["grounded_n"] = gn_;
    put_time(out, "grounded_t0", gt0_);
    out["grounded_search_from"] = g_search_from_;
    out["grounded_W"] = pack_array(std::vector<double>{gW_re_, gW_im_});
    const std::pair<const char*, const std::vector<double>*> arrays[] = {
        {"grounded_y0", &gy0_},     {"grounded_yd0", &gyd0_},   {"grounded_amp0", &gamp0_}, {"grounded_c_re", &gc_re_},
        {"grounded_c_im", &gc_im_}, {"grounded_P_re", &gP_re_}, {"grounded_P_im", &gP_im_}, {"grounded_P_abs", &gP_abs_}};
    for (const auto& [key, values] : arrays) out[key] = pack_array(*values);
  }
}

void ExactEngine::restore(const StateArchive& in) {
  if (saved_value<int>(in, "layout") != kLayout)
    throw StateArchiveError("saved state: the exact engine's fields are of another layout");
  const auto n = static_cast<std::size_t>(n_);
  const std::size_t pairs = n > 1 ? n - 1 : 0;
  now_ = saved_time(in, "now");
  hi_ = unpack_array<int>(in, "hi", n);
  lo_of_ = unpack_array<int>(in, "lo_of", n);
  t0_ = unpack_array<Time>(in, "t0", n);
  V0_ = unpack_array<double>(in, "V0", n);
  search_from_ = unpack_array<double>(in, "search_from", n);
  grazing_streak_ = unpack_array<int>(in, "grazing_streak", n);
  hold_until_ = unpack_array<Time>(in, "hold_until", n);
  generation_ = unpack_array<std::uint64_t>(in, "generation", n);
  formations_ = saved_value<std::uint64_t>(in, "formations");
  y0_ = unpack_array<double>(in, "y0", n);
  yd0_ = unpack_array<double>(in, "yd0", n);
  amp0_ = unpack_array<double>(in, "amp0", n);
  gaps_.t = unpack_array<Time>(in, "gap_t", pairs);
  gaps_.s = unpack_array<double>(in, "gap_s", pairs);
  gaps_.c = unpack_array<double>(in, "gap_c", pairs);
  gap_ma_ = unpack_array<double>(in, "gap_ma", n);
  gap_mb_ = unpack_array<double>(in, "gap_mb", n);
  floor_t_ = saved_time(in, "floor_t");
  floor_s_ = saved_value<double>(in, "floor_s");
  floor_u_ = saved_value<double>(in, "floor_u");

  schedule_.reset(n_, true);
  const auto slots = static_cast<std::size_t>(schedule_.slots());
  const std::vector<Time> slot_time = unpack_array<Time>(in, "slot_time", slots);
  const std::vector<std::uint8_t> kind = unpack_array<std::uint8_t>(in, "slot_kind", slots);
  const std::vector<int> pair = unpack_array<int>(in, "slot_pair", slots);
  const std::vector<double> tau = unpack_array<double>(in, "slot_tau", slots);
  for (std::size_t s = 0; s < slots; ++s) {
    if (kind[s] > static_cast<std::uint8_t>(SlotKind::PlateSwitch))
      throw StateArchiveError("saved state: an event of no known kind");
    schedule_.set(static_cast<int>(s), slot_time[s], SlotDetail{static_cast<SlotKind>(kind[s]), pair[s], tau[s]});
  }

  const std::vector<std::uint64_t> counts = unpack_array<std::uint64_t>(in, "counts", kCounts);
  std::memcpy(static_cast<void*>(&counters_), counts.data(), sizeof(ExactCounters));
  shortcut_events_ = saved_value<std::uint64_t>(in, "shortcut_events");
  audit_draws_ = saved_value<std::uint64_t>(in, "audit_draws");

  cache_.lo = saved_value<int>(in, "cache_lo");
  cache_.generation = saved_value<std::uint64_t>(in, "cache_generation");
  cache_.t = saved_time(in, "cache_t");
  cache_.y = unpack_array<double>(in, "cache_y", cache_.y.size());
  cache_.yd = unpack_array<double>(in, "cache_yd", cache_.yd.size());

  if (plate_ != nullptr) {
    piece_.t0 = saved_time(in, "piece_t0");
    piece_.end = saved_time(in, "piece_end");
    const std::vector<double> zva = unpack_array<double>(in, "piece_zva", 3);
    piece_.z = zva[0];
    piece_.v = zva[1];
    piece_.a = zva[2];
    grounded_ = saved_value<bool>(in, "grounded");
    gn_ = saved_value<int>(in, "grounded_n");
    gt0_ = saved_time(in, "grounded_t0");
    g_search_from_ = saved_value<double>(in, "grounded_search_from");
    const std::vector<double> W = unpack_array<double>(in, "grounded_W", 2);
    gW_re_ = W[0];
    gW_im_ = W[1];
    const std::pair<const char*, std::vector<double>*> arrays[] = {
        {"grounded_y0", &gy0_},     {"grounded_yd0", &gyd0_},   {"grounded_amp0", &gamp0_}, {"grounded_c_re", &gc_re_},
        {"grounded_c_im", &gc_im_}, {"grounded_P_re", &gP_re_}, {"grounded_P_im", &gP_im_}, {"grounded_P_abs", &gP_abs_}};
    for (const auto& [key, values] : arrays) *values = unpack_array<double>(in, key, values->size());
    if (gn_ < 0 || gn_ > n_ || (grounded_ && (gn_ < 1 || hi_[0] != gn_ - 1))) {
      throw StateArchiveError("saved state: the grounded cluster does not fit the clusters");
    }
  }

  // The clusters must tile the chain, each particle naming its cluster's lowest one.
  for (std::size_t lo = 0; lo < n;) {
    const int hi = hi_[lo];
    if (hi < static_cast<int>(lo) || hi >= n_)
      throw StateArchiveError("saved state: the exact engine's clusters do not tile the chain");
    for (int p = static_cast<int>(lo); p <= hi; ++p) {
      if (lo_of_[p] != static_cast<int>(lo))
        throw StateArchiveError("saved state: the exact engine's clusters do not tile the chain");
    }
    lo = static_cast<std::size_t>(hi) + 1;
  }
  if (!now_.finite() || !std::isfinite(now_.low())) throw StateArchiveError("saved state: the exact engine's time is not finite");
  check_restored_schedule();
  state_valid_ = false;
}

// What a saved state must satisfy for the events it schedules to act on existing clusters and pairs
// (a file corrupted or of another build must not send the engine out of its arrays): every pending
// time is +inf or not before now; a cluster's event belongs to a cluster's lowest particle and names
// one of its pairs (of the grounded cluster, -1 for the plate's virtual overlap); a gap's event
// belongs to an open pair; a floor event needs a floor (a plate's switch, a plate); no generation
// lies ahead of the count of formations.
void ExactEngine::check_restored_schedule() const {
  const auto bad = [](const char* what) { throw StateArchiveError(std::string("saved state: ") + what); };
  for (int slot = 0; slot < schedule_.slots(); ++slot) {
    const Time& t = slot_time(slot);
    if (std::isnan(t.value()) || std::isnan(t.low())) bad("an event at no time");
    if (t.value() == kInf) continue;
    if (t < now_) bad("an event before the engine's time");
    const SlotDetail& d = schedule_.detail(slot);
    const auto [family, index] = schedule_.slot_of(slot);
    if (family == EventFamily::Local) {
      if (lo_of_[index] != index) bad("a cluster's event at a particle that is not a cluster's lowest");
      const bool grounded = index == 0 && grounded_;
      const int first = grounded ? -1 : index, end = grounded ? gn_ - 1 : hi_[index];
      if (d.kind == SlotKind::ContactEnd || d.kind == SlotKind::PassThrough) {
        if (d.pair < first || d.pair >= end) bad("a cluster's event at a pair outside it");
        if (d.kind == SlotKind::ContactEnd && !(d.tau >= 0.0 && std::isfinite(d.tau))) bad("a contact's end at no local time");
      } else if (d.kind != SlotKind::Refresh) {
        bad("a cluster's event of another family");
      }
    } else if (family == EventFamily::Interaction) {
      if (lo_of_[index] == lo_of_[index + 1]) bad("a gap's event at a closed pair");
      if (d.kind != SlotKind::ContactBegin && d.kind != SlotKind::Refresh) bad("a gap's event of another family");
    } else {
      const bool plate_switch = d.kind == SlotKind::PlateSwitch && plate_ != nullptr;
      if (floor_ == nullptr || !(d.kind == SlotKind::FloorHit || d.kind == SlotKind::Refresh || plate_switch))
        bad("a floor event without a floor, or of another family");
    }
  }
  for (int lo = 0; lo < n_; lo = hi_[lo] + 1) {
    if (generation_[lo] > formations_) bad("a cluster formed after the last formation");
  }
  if (cache_.generation > formations_) bad("cached modes of a cluster formed after the last formation");
}

}  // namespace granchain
