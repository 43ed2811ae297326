#include "haptics/tool/wrench_limiter.h"

#include <cmath>

#include "haptics/io/wrench_output.h"

namespace haptics {
namespace {

// Scales x down to length `limit` if longer; true if it did.
bool ClampNorm(Vector3* x, double limit) {
  const double n = x->norm();
  if (!(n > limit)) return false;
  *x *= limit / n;
  return true;
}

}  // namespace

WrenchLimiter::WrenchLimiter(const DeviceConfig& device, double dt)
    : max_force_(device.max_force), max_torque_(device.max_torque),
      max_df_(device.max_force_rate * dt), max_dtau_(device.max_torque_rate * dt) {}

Wrench WrenchLimiter::Apply(const Wrench& raw, double scale, int32_t* flags) {
  Wrench out{scale * raw.f_W, scale * raw.tau_W};

  if (out.AllFinite()) {
    const bool force_clamped = ClampNorm(&out.f_W, max_force_);
    const bool torque_clamped = ClampNorm(&out.tau_W, max_torque_);
    if (force_clamped) ++counts_.force_saturated, *flags |= kFlagForceSaturated;
    if (torque_clamped) ++counts_.torque_saturated, *flags |= kFlagTorqueSaturated;
    if (force_clamped || torque_clamped) ++counts_.saturated;

    Vector3 df = out.f_W - previous_.f_W;
    Vector3 dtau = out.tau_W - previous_.tau_W;
    const bool force_limited = ClampNorm(&df, max_df_);
    const bool torque_limited = ClampNorm(&dtau, max_dtau_);
    if (force_limited || torque_limited) {
      ++counts_.rate_limited;
      *flags |= kFlagRateLimited;
      out.f_W = previous_.f_W + df;
      out.tau_W = previous_.tau_W + dtau;
    }
  }
  if (!out.AllFinite()) {
    ++counts_.nonfinite;
    out = Wrench{};
  }
  previous_ = out;
  return out;
}

}  // namespace haptics
