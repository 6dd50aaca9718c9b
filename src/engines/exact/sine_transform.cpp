#include "engines/exact/sine_transform.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace granchain {

namespace {
// FFTW's planner is not thread-safe (sweeps run one engine per thread); executing a plan is.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}
}  // namespace

struct SineTransform::Plan {
  double* buffer = nullptr;  // M values, FFTW-aligned; the transform runs in place here
  fftw_plan plan = nullptr;
  double scale = 0;
};

SineTransform::SineTransform(int M) : M_(M), plan_(std::make_unique<Plan>()) {
  if (M < 1) throw std::invalid_argument("SineTransform: M must be >= 1");
  plan_->scale = 0.5 * std::sqrt(2.0 / (M + 1));
  const std::lock_guard<std::mutex> lock(planner_mutex());
  plan_->buffer = fftw_alloc_real(static_cast<std::size_t>(M));
  if (plan_->buffer != nullptr) {
    plan_->plan = fftw_plan_r2r_1d(M, plan_->buffer, plan_->buffer, FFTW_RODFT00, FFTW_ESTIMATE | FFTW_NO_SIMD);
  }
  if (plan_->plan == nullptr) {
    fftw_free(plan_->buffer);
    throw std::runtime_error("SineTransform: FFTW could not plan a sine transform");
  }
}

SineTransform::~SineTransform() {
  const std::lock_guard<std::mutex> lock(planner_mutex());
  fftw_destroy_plan(plan_->plan);
  fftw_free(plan_->buffer);
}

void SineTransform::apply(const double* in, double* out) const {
  double* buf = plan_->buffer;
  std::copy_n(in, M_, buf);
  fftw_execute(plan_->plan);
  const double scale = plan_->scale;
  for (int i = 0; i < M_; ++i) out[i] = scale * buf[i];
}

bool SineTransform::pays_off(int M) { return M >= 31; }

}  // namespace granchain
