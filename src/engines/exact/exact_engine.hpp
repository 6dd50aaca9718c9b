#pragma once
// Exact event-driven engine. Between changes of the contact set the equations of motion
// of the spring-dashpot chain (Eq. force-0) are linear with constant coefficients, so the motion
// is known in closed form:
//   - a free particle flies on a parabola;
//   - a cluster of n touching particles has its centre of mass in free fall and its n-1 overlaps
//     in n-1 independent damped sine modes (cluster_modes.hpp);
// and time jumps from one event to the next: a gap closing (contact begins), an overlap returning
// to zero (contact ends: one counted collision), particle 1 reaching the floor. Each event time is
// the first root of a polynomial of degree <= 2 plus damped modes; it is found by steps that are
// proven root-free (Taylor lower bounds whose remainders are bounded by the modes' amplitudes, which
// never grow), which converge onto the root to round-off, so no event can be skipped.
//
// Positions and velocities are never differenced as absolute values. The engine keeps the gap of
// every open pair with the relative velocity of the clusters on either side, the overlaps of
// closed pairs and their rates (as mode amplitudes), and the height of particle 1 above the floor,
// each as a value at a reference time plus displacements since then: an overlap of 1e-7 d at
// k = 1e12 keeps its full relative precision, and so does a relative speed of 1e-20 between
// particles that move at speed 1 (gravity cancels in every gap). Absolute velocities enter only the
// floor height and the reported state.
//
// A vibrating plate (model/plate_motion.hpp) is one more event family of the same skeleton
// (exact_plate.cpp): particle 1 flying above it meets the surface at the first root of a parabola
// minus the surface (a piece's polynomial, or a sinusoid), and the cluster touching it ("grounded")
// is the symmetric half of a mirror cluster of twice its size (tables_[2n]) whose middle overlap,
// X = 2 x_w, is forced by 2 (g + a_p): its overlaps are a particular solution (constant on each piece
// of a piecewise drive; for the sine, a constant plus a sinusoid in every mode) plus the mirror
// cluster's free symmetric modes, searched as any cluster's. A piece's end is an event (the
// grounded cluster re-forms about the new particular solution; the sawtooth's drop releases it).
#include <cstdint>
#include <limits>
#include <vector>

#include "engines/exact/cluster_modes.hpp"
#include "engines/engine.hpp"
#include "engines/chain_schedule.hpp"
#include "engines/fine_time.hpp"
#include "model/chain_parameters.hpp"
#include "model/floor.hpp"

namespace granchain {

struct ExactOptions {
  // After every event, evaluate every overlap, gap and the floor height at kAuditInstants random
  // instants before the next event and count those with the wrong sign (EngineCounters); the
  // trajectory is the same with and without it.
  bool audit = false;
  // Binary contacts of two free particles take the short path of exact_binary.cpp. The trajectory
  // is the same bit for bit with and without it (tests compare the two).
  bool pair_shortcuts = true;
};

// The exact engine's own counts: the generic ones, where its prediction work goes, and what
// below_resolution() and audit() report. Saved as one row in a checkpoint: a change of their order
// raises kLayout in exact_checkpoint.cpp.
struct ExactCounters {
  std::uint64_t steps = 0, contact_ends = 0, floor_hits = 0;  // as EngineCounters
  std::uint64_t search_steps = 0;  // root-free steps of the event searches
  // Event predictions solved in closed form (a pair's contact end, two free particles, a free
  // particle over the floor), those a lower bound ruled out with no step (a gap or floor height
  // next to a cluster, first_root), and those searched step by step: a cluster's contact ends
  // (their steps counted apart) or a gap or floor height.
  std::uint64_t closed_form_predictions = 0;
  std::uint64_t bound_exclusions = 0;
  std::uint64_t cluster_searches = 0;
  std::uint64_t cluster_search_steps = 0;
  std::uint64_t edge_searches = 0;
  std::uint64_t grazing_contacts = 0, resolution_skips = 0, held_contacts = 0;  // ResolutionCounters
  std::uint64_t audit_instants = 0, audit_values = 0, audit_violations = 0;    // AuditCounters
};

class ExactEngine final : public Engine {
 public:
  // floor == nullptr: no floor (free space). The chain feels gravity p.g (set 0 for free space).
  ExactEngine(const ChainParameters& p, const ChainState& initial, FloorDrive* floor, ExactOptions options = {});

  void advance_to(double t, EventSink& sink) override;
  const ChainState& state() const override;
  double time() const override { return now_.value(); }
  EngineCounters counters() const override { return {counters_.steps, counters_.contact_ends, counters_.floor_hits}; }
  ResolutionCounters below_resolution() const override {
    return {counters_.grazing_contacts, counters_.held_contacts, counters_.resolution_skips};
  }
  AuditCounters audit() const override { return {counters_.audit_instants, counters_.audit_values, counters_.audit_violations}; }
  // All its counts, for its tests and benchmarks.
  const ExactCounters& work() const { return counters_; }

  // Kinetic + elastic (k x^2 / 2 per closed contact) + gravitational energy at time(), per unit
  // mass, with z measured from the floor level of the centres (d/2). For conservation tests.
  double mechanical_energy_per_mass() const;
  // Overlaps x_i = d - (z_{i+1} - z_i) at time() straight from the stored gaps and modes (full
  // relative precision, unlike differences of state().z).
  std::vector<double> overlaps() const;
  // A checkpoint (exact_checkpoint.cpp): every cluster, gap, the floor height, the schedule, the
  // plate's piece and grounded cluster, the mode cache and the counts, as stored (no value is
  // recomputed, so the restored engine goes on bit for bit).
  void save(StateArchive& out) const override;
  void restore(const StateArchive& in) override;
  // Events handled by the short paths of exact_binary.cpp (ExactOptions::pair_shortcuts).
  std::uint64_t shortcut_events() const { return shortcut_events_; }

 private:
  using Time = FineTime;  // absolute times; local times (since a reference time) are doubles
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  // Root-free steps allowed per prediction; past that the prediction becomes a "refresh" at the
  // last proven-safe time, where the search starts again (no physics happens at a refresh).
  static constexpr int kMaxIterations = 400;
  // Steps after which a search counts values within round-off of zero as zero.
  static constexpr int kStallSteps = 32;
  // Below this fraction of tau_c the engine does not resolve a function that touches zero within
  // round-off (grazing contacts whose overlaps are far below the round-off of their neighbours').
  static constexpr double kResolutionSkip = 1e-6;

  // Saved by number in a checkpoint: a change here raises kLayout in exact_checkpoint.cpp.
  enum class SlotKind : std::uint8_t { None, ContactEnd, ContactBegin, FloorHit, PassThrough, Refresh, PlateSwitch };
  void check_restored_schedule() const;  // exact_checkpoint.cpp
  // What a slot's event is (its time is the schedule's).
  struct SlotDetail {
    SlotKind kind = SlotKind::None;
    int pair = 0;
    double tau = 0;  // for cluster events: the root in the cluster's own time (t rounds t0 + tau)
  };
  struct Root {
    enum Kind { Found, None, Refresh } kind;
    double sigma;
    int which;
  };
  // A function f(s) = c0 + c1 s + p2 s^2 / 2 + sum over up to two clusters of
  // sign * sum_j coef_j y_j(tau0 + s): a gap (s >= 0 counted from now) or the height of particle 1
  // above the floor.
  struct EdgeTerm {
    const ClusterModeTable* table;
    const double* y0;
    const double* yd0;
    const double* amp0;  // sqrt(E_j) / omega0_j at formation
    const double* coef;
    double sign;
    double tau0;
  };
  struct EdgeFunction {
    double c0 = 0, c1 = 0, p2 = 0;
    EdgeTerm term[2];
    int terms = 0;
    bool modes_nonnegative = false;  // every term's mode part is >= 0 up to sigma_max (predict_gap)
    // sum over the terms of |a_j| sqrt(E_j) / omega0_j (edge_reach): no mode part exceeds it.
    double reach = 0;
    // Round-off of c0 (a difference of stored heights): values up to this (plus the mode part's
    // round-off) are zero as far as double precision can tell.
    double noise = 0;
    // A sinusoidal plate: + sin_amp sin(sin_phase + sin_omega s) (0: none). It is in reach too.
    double sin_amp = 0, sin_phase = 0, sin_omega = 0;
  };

  // --- clusters (indexed by their lowest particle lo) ---
  int cluster_size(int lo) const { return hi_[lo] - lo + 1; }
  // x, xd: the n-1 overlaps and their rates; V: the centre-of-mass velocity at t.
  void form_cluster(int lo, int hi, Time t, const double* x, const double* xd, double V);
  // Overlaps (x, xd: n-1 values) and velocities (v: n values) of the cluster at time t.
  void cluster_state(int lo, Time t, double* x, double* xd, double* v) const;
  // Overlaps and rates from the modes y, yd, and the velocities relative to the centre of mass
  // (u: n values, mean zero), built from the overlap rates alone.
  void cluster_relative(int lo, const double* y, const double* yd, double* x, double* xd, double* u) const;
  double com_velocity(int lo, Time t) const { return V0_[lo] - g_ * (t - t0_[lo]); }
  void modes_at(int lo, double tau, double* y, double* yd) const;
  // Mode part of the bottom (top = false) or top particle's height: its displacement from the
  // centre of mass up to a constant (0 for a single particle).
  double edge_mode(int lo, bool top, Time t) const {
    if (lo == 0 && grounded_) return top ? grounded_edge_top(t) : 0.0;
    return hi_[lo] == lo ? 0.0 : cluster_edge_mode(lo, top, t);
  }
  double cluster_edge_mode(int lo, bool top, Time t) const;  // clusters of two or more
  // Height coordinate of particle 1: centre-of-mass displacement since formation plus mode part.
  double bottom_u(Time t) const { return bottom_u_mode(t, edge_mode(0, false, t)); }
  double bottom_u_mode(Time t, double mode) const;  // the same, given the mode part at t
  EdgeTerm edge_term(int lo, bool top, double sign, Time t) const;

  // --- gaps and the floor height, each a value at a reference time ---
  // Open pair i at time t: gap_s + gap_c (t - gap_t) + [mode part of the upper edge since gap_t]
  // - [mode part of the lower edge since gap_t]; gap_c is the relative velocity of the two
  // clusters' centres of mass (constant while neither re-forms: gravity cancels).
  double gap_at(int i, Time t) const;
  // The same from the mode parts of the lower cluster's top (m_a) and the upper one's bottom (m_b)
  // at t.
  double gap_from_edges(int i, Time t, double m_a, double m_b) const {
    return gap_line(i, t) + (m_b - gap_mb_[i]) - (m_a - gap_ma_[i]);
  }
  // The line part of gap i: s + c (t - t_i), plus -(g + a_p) (t - t_i)^2 / 2 above a grounded
  // cluster, whose "centre of mass" is the plate.
  double gap_line(int i, Time t) const {
    if (i != ground_gap()) return gaps_.line_at(i, t);
    const double tau = t - gaps_.t[i];
    return gaps_.s[i] + tau * (gaps_.c[i] - 0.5 * g_ * tau) - ground_zdev(gaps_.t[i], t);
  }
  void sync_gap(int i, Time t);    // move the reference of open gap i to t (clusters unchanged)
  void sync_gap_edges(int i, Time t, double m_a, double m_b);  // the same, given the edges' mode parts at t
  void rebase_gap(int i, Time t);  // after a neighbour re-formed at t: new mode-part origin
  void sync_floor(Time t);
  void sync_floor_mode(Time t, double mode);  // the same, given particle 1's mode part at t
  void rebase_floor(Time t);

  // --- prediction ---
  void predict_cluster(int lo);
  void predict_gap(int i);
  bool has_holds(int lo) const;  // a held pair in cluster lo (merge)
  // sqrt(2/n) sum_j sqrt(E_j) / omega0_j: no overlap of cluster lo exceeds it at any later time.
  double overlap_reach(int lo) const;
  void predict_floor();
  // The first root of f in [sigma0, sigma_max]; f is known positive before sigma0 (bound_clear).
  Root first_root(const EdgeFunction& f, double sigma_max, double sigma0) const;
  Root first_internal_root(int lo, bool watch_pass_through) const;
  // The modes of a cluster (table tab, y0 and yd0 at formation) at its local time tau with their
  // derivatives 0 .. P-1 (row n of yn, M values each), each amplitude times bound[2] and bound[P]
  // (amp2, ampP), and the sums of amp2 and of the amplitudes added to sum2 and sum_amp.
  static void mode_jets(const ClusterModeTable& tab, const double* y0, const double* yd0, double tau, double* yn, double* amp2,
                        double* ampP, double& sum2, double& sum_amp);
  double pair_contact_end(int lo) const;  // two-particle cluster: closed form

  // --- events ---
  void handle(int slot, const Time& t, EventSink& sink);
  void split(int lo, int pair, Time t, double tau, EventSink& sink);
  // The end of split: the two parts formed at t from their overlaps x, xd (null for single
  // particles), the old centre of mass's velocity V and the parts' centre-of-mass velocities
  // relative to it; gaps and the floor rebased, the event reported, everything re-predicted.
  void part(int lo, int pair, int hi, Time t, const double* x, const double* xd, double V, double u_lower, double u_upper,
            double speed, EventSink& sink);
  void merge(int pair, Time t, EventSink& sink);
  void floor_hit(Time t, EventSink& sink);
  void refresh_cluster(int lo, Time t);

  // --- binary contacts of two free particles (exact_binary.cpp): the same arithmetic as merge
  // and split, without the cluster machinery ---
  // A contact begun at zero overlap between two particles: it ends at tau = pi / w.
  bool is_fresh_pair(int lo) const { return hi_[lo] == lo + 1 && y0_[lo] == 0.0; }
  void merge_free_pair(int pair, Time t, EventSink& sink);
  void split_fresh_pair(int lo, Time t, EventSink& sink);
  // How far a gap's or the floor height's lower bound c0 - margin * reach + c1 s + p2 s^2 / 2
  // provably stays positive (0 when it is not positive at s = 0).
  double bound_clear(double c0, double c1, double p2, double reach, bool modes_nonnegative) const;
  // That span reaches sigma_max: no event, and no edge function needs building (counted).
  bool bound_excludes(double clear, double sigma_max) const {
    if (!(clear > 0) || clear < sigma_max) return false;
    ++counters_.bound_exclusions;
    return true;
  }
  // sum_j |coef_j| amp0_j of the edge of cluster lo (top or bottom, two or more particles): no
  // edge mode part exceeds it.
  double edge_reach(int lo, bool top, double acc) const;  // acc + the sum
  // c0 - margin * reach: the value at zero of f's lower bound (first_root). The margin is 1e-10
  // when every mode part is >= 0 (only round-off below zero), else 1.
  static double bound_at_zero(double c0, double reach, bool modes_nonnegative) {
    return c0 - (modes_nonnegative ? 1e-10 : 1.0) * reach;
  }
  bool shortcuts_ = true;
  std::uint64_t shortcut_events_ = 0;

  // --- a vibrating plate (exact_plate.cpp) ---
  // The current piece of the plate's motion: z_p = z + v tau + a tau^2 / 2 from t0 to end.
  struct Piece {
    Time t0 = 0, end = 0;
    double z = 0, v = 0, a = 0;  // a = 0 for the sine (its a_p is in the particular solution)
  };
  double plate_z(Time t) const {
    if (sine_) return plate_->amplitude() * std::sin(plate_phase(t));
    const double tau = t - piece_.t0;
    return piece_.z + tau * (piece_.v + 0.5 * piece_.a * tau);
  }
  double plate_v(Time t) const {
    if (sine_) return plate_->amplitude() * plate_->omega() * std::cos(plate_phase(t));
    return piece_.v + piece_.a * (t - piece_.t0);
  }
  // The sine's phase omega t + phi at a FineTime t (both parts of t multiplied).
  double plate_phase(Time t) const { return plate_->omega() * t.value() + (plate_->phase() + plate_->omega() * t.low()); }
  // The grounded cluster's top particle apart from its free modes: the plate plus the particular
  // solution's top edge, Z(t) (sine: Im(W e^{i theta}) with W = A + sum_j top_j c_j). Its velocity,
  // and Z(t) - Z(t_ref) - Z'(t_ref)(t - t_ref): what bends the line of the gap above the cluster.
  double ground_zdot(Time t) const;
  double ground_zdev(Time t_ref, Time t) const;
  void start_piece(Time t);  // the piece that begins at t (or contains it)
  int ground_gap() const { return grounded_ && hi_[0] + 1 < n_ ? hi_[0] : -1; }
  // xr, xdr: the n real overlaps of the grounded cluster 0..n-1 (X = 2 x_w, then pairs 0..n-2) and
  // their rates at t.
  void form_grounded(int n, Time t, const double* xr, const double* xdr);
  void grounded_modes(double tau, double* y, double* yd) const;
  // Real overlaps, rates (n each) and velocities (n) of the grounded cluster at its local time tau
  // (absolute time t).
  void grounded_state(double tau, Time t, double* xr, double* xdr, double* v) const;
  double grounded_edge_top(Time t) const;  // mode part of its top particle's height
  double grounded_reach_top(double acc) const;
  double grounded_offset(int i) const;  // particular solution of virtual overlap i on this piece
  Root first_grounded_root(bool watch_pass_through) const;
  void predict_grounded();
  void predict_ground_gap(int i);
  void plate_contact(Time t, EventSink& sink);
  // Particle 1 leaves the plate at t (local time tau); then the floor is re-predicted unless a new
  // piece is about to start.
  void plate_release(Time t, double tau, EventSink& sink, bool predict_floor_after);
  void grounded_split(int pair, Time t, double tau, EventSink& sink);
  void grounded_merge(int pair, Time t, EventSink& sink);
  void plate_switch(Time t, EventSink& sink);
  // The grounded cluster re-formed from its own state at t (about a new piece's particular
  // solution when new_piece), then re-predicted with its gap above and the floor.
  void reform_grounded(Time t, bool new_piece);
  const PlateMotion* plate_ = nullptr;
  Piece piece_;
  bool grounded_ = false;
  int gn_ = 0;                  // particles of the grounded cluster
  Time gt0_ = 0;                // its formation
  double g_search_from_ = 0;    // local time from which its contact ends are searched
  bool sine_ = false;           // the plate is the sine
  std::vector<double> gy0_, gyd0_, gamp0_;  // its free mirror modes at formation, amplitude bounds (2n - 1)
  // The sine's particular solution: mode j is Im(c_j e^{i theta}), virtual overlap i Im(P_i e^{i theta});
  // |P_i|; W of ground_zdot.
  std::vector<double> gc_re_, gc_im_, gP_re_, gP_im_, gP_abs_;
  double gW_re_ = 0, gW_im_ = 0;
  mutable std::vector<double> gx_, gxd_, gy_, gyd_, gxr_, gxdr_, gv_, gf_, gfd_;  // scratch

  // --- audit (exact_audit.cpp) ---
  static constexpr int kAuditInstants = 2;
  void audit_interval(Time a, Time b);
  bool audit_ = false;
  std::uint64_t audit_draws_ = 0;

  // --- schedule: the local family holds the clusters' events (slot lo), the interaction family the
  // gaps', and the floor (chain_schedule.hpp) ---
  int cluster_slot(int lo) const { return schedule_.local(lo); }
  int gap_slot(int i) const { return schedule_.interaction(i); }
  int floor_slot() const { return schedule_.floor(); }
  const Time& slot_time(int slot) const { return schedule_.time(slot); }
  void set_slot(int slot, const Time& t, SlotKind kind, int pair, double tau = 0.0);
  // A gap or floor slot with no event before `horizon`, the time of a neighbouring cluster's own
  // event (which re-predicts this slot, and wins a tie as the lower slot): a time the slot holds
  // from an earlier prediction is left as it is when it is not before the horizon, so it can
  // never fire; an earlier one is cleared. This saves schedule updates, not physics.
  void clear_slot_before(int slot, const Time& horizon, int pair) {
    if (!(slot_time(slot) >= horizon)) set_slot(slot, kInf, SlotKind::None, pair);
  }

  int n_;
  double d_, g_, k_over_m_, D_, tau_c_;
  FloorDrive* floor_;
  ClusterModeTables tables_;

  std::vector<int> hi_;            // hi_[lo]: top particle of the cluster whose bottom is lo
  std::vector<int> lo_of_;         // lo_of_[p]: bottom particle of p's cluster
  std::vector<Time> t0_;           // formation time
  std::vector<double> V0_;         // centre-of-mass velocity then
  std::vector<double> search_from_;  // local time from which the cluster's contact ends are searched
  // Repeated grazing contacts of one pair (see merge): consecutive grazing begins of pair i, and
  // the absolute time before which the overlap of pair i is not allowed to end its contact.
  std::vector<int> grazing_streak_;
  std::vector<Time> hold_until_;
  std::vector<std::uint64_t> generation_;  // distinct for every formation (mode-cache key)
  std::uint64_t formations_ = 0;
  std::vector<double> y0_, yd0_;   // mode amplitudes and rates at formation: lo + j, j < n-1
  std::vector<double> amp0_;       // sqrt(E_j) / omega0_j at formation (bounds |y_j| from then on)
  // Open pair i: the gap s at the reference time t, and c the relative velocity of the centres of
  // mass of the clusters on either side (chain_schedule.hpp); beside them the mode parts of the
  // lower cluster's top edge and the upper cluster's bottom edge at t.
  GapLines<Time> gaps_;
  std::vector<double> gap_ma_, gap_mb_;
  Time floor_t_ = 0;
  double floor_s_ = 0, floor_u_ = 0;       // z_1 - d/2 at floor_t_, and u then

  ChainSchedule<Time, SlotDetail> schedule_;

  Time now_ = 0;
  mutable ExactCounters counters_;

  mutable ChainState state_;
  mutable bool state_valid_ = false;
  mutable std::vector<double> sx_, sxd_, sv_, sv2_, shq_;  // scratch
  mutable std::vector<double> sy2_[2], sx2_[2];  // scratch: modes and rates (split), overlaps and rates (searches)
  mutable std::vector<double> smode_, samp_;    // searches: modes and derivatives, scaled amplitudes
  // The modes of one cluster at one time, kept because an event evaluates the same cluster at
  // the same instant several times (gaps below and above, floor, state).
  struct ModeCache {
    int lo = -1;
    std::uint64_t generation = 0;
    Time t = 0;
    std::vector<double> y, yd;
  };
  mutable ModeCache cache_;
  // Modes of cluster lo at time t (through the cache); pointers valid until the next call.
  void cached_modes(int lo, Time t, const double*& y, const double*& yd) const;
  // Makes y, yd (computed elsewhere) the cache's modes of cluster lo at time t.
  void seed_cache(int lo, Time t, const double* y, const double* yd) const;
  // The binary contact begun at zero overlap (two free particles meeting): it ends at
  // tau = pi / w (= tau_c) with rate -restitution times the initial one (modes_at, pair_contact_end).
  struct PairContact {
    double tau = -1.0, restitution = 0.0;
  } pair_;
  const ClusterModeTable* pair_table_ = nullptr;  // tables_[2] (N >= 2)
};

}  // namespace granchain
