#pragma once
// A clock that does not lose resolution as time grows: the time is the unevaluated sum hi + lo of
// two doubles with |lo| <= ulp(hi) / 2 (a "double-double", 106 significant bits). At t = 1e4 it
// resolves 1e-28, so a contact lasting tau_c = 2e-10 (k = 1e20) is timed to 1e-18 of tau_c, where
// a plain double (ulp = 1.8e-12) would not resolve it at all. Event-driven engines keep every
// reference time (a cluster's formation, a gap's reference) as FineTime and compute in local
// time: the difference of two FineTimes, rounded once to a double with full relative precision.
//
// The error-free transformation is Knuth's two-sum (exact in IEEE arithmetic with round-to-nearest,
// which the project's compile flags keep: no -ffast-math).
#include <cmath>
#include <limits>

namespace granchain {

class FineTime {
 public:
  constexpr FineTime() = default;
  constexpr FineTime(double t) : hi_(t) {}  // NOLINT: every double is a time
  // The time hi + lo given as the pair value(), low() of a FineTime (an event's t and t_low).
  static FineTime from_parts(double hi, double lo) { return FineTime(hi) + lo; }

  static constexpr FineTime infinity() { return FineTime(std::numeric_limits<double>::infinity()); }
  static constexpr FineTime minus_infinity() { return FineTime(-std::numeric_limits<double>::infinity()); }

  // The time rounded to the nearest double.
  constexpr double value() const { return hi_; }
  constexpr double low() const { return lo_; }
  bool finite() const { return std::isfinite(hi_); }

  // t + s, rounded once to 106 bits.
  FineTime operator+(double s) const {
    if (!std::isfinite(hi_) || !std::isfinite(s)) return FineTime(hi_ + s);
    double e;
    const double sum = two_sum(hi_, s, e);
    return normalised(sum, e + lo_);  // |e + lo| <= ulp(sum) unless hi + s cancelled: two-sum
  }
  FineTime& operator+=(double s) { return *this = *this + s; }

  // a - b rounded to a double (exactly the nearest double when |lo| terms are small).
  friend double operator-(const FineTime& a, const FineTime& b) {
    if (!std::isfinite(a.hi_) || !std::isfinite(b.hi_)) return a.hi_ - b.hi_;
    double e;
    const double d = two_sum(a.hi_, -b.hi_, e);
    return d + (e + (a.lo_ - b.lo_));
  }

  friend bool operator==(const FineTime& a, const FineTime& b) { return a.hi_ == b.hi_ && a.lo_ == b.lo_; }
  friend bool operator!=(const FineTime& a, const FineTime& b) { return !(a == b); }
  // Written with | and & rather than || and &&: no branch on the outcome (event queues compare
  // times whose order is unpredictable).
  friend bool operator<(const FineTime& a, const FineTime& b) {
    return (a.hi_ < b.hi_) | ((a.hi_ == b.hi_) & (a.lo_ < b.lo_));
  }
  friend bool operator>(const FineTime& a, const FineTime& b) { return b < a; }
  friend bool operator<=(const FineTime& a, const FineTime& b) { return !(b < a); }
  friend bool operator>=(const FineTime& a, const FineTime& b) { return !(a < b); }

 private:
  constexpr FineTime(double hi, double lo) : hi_(hi), lo_(lo) {}
  // s + e = a + b exactly (Knuth).
  static double two_sum(double a, double b, double& e) {
    const double s = a + b;
    const double bb = s - a;
    e = (a - (s - bb)) + (b - bb);
    return s;
  }
  // The pair (s, e) with |e| <= ulp(s) / 2 and s + e = a + b.
  static FineTime normalised(double a, double b) {
    double e;
    const double s = two_sum(a, b, e);
    return FineTime(s, e);
  }
  double hi_ = 0.0, lo_ = 0.0;
};

}  // namespace granchain
