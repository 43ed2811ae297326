#include "haptics/tool/device_velocity.h"

#include <cmath>

#include "haptics/tool/rotation_vector.h"

namespace haptics {
namespace {

// Sender time steps outside this range are not trusted for differencing.
constexpr double kMinStep = 1e-5;  // s
constexpr double kMaxStep = 0.1;   // s

}  // namespace

DeviceVelocityEstimator::DeviceVelocityEstimator(double cutoff_hz) : cutoff_hz_(cutoff_hz) {}

void DeviceVelocityEstimator::Reset(const PoseSample& pose) {
  previous_ = pose;
  has_previous_ = true;
  v_W_ = pose.has_velocity ? pose.v_WD : Vector3::Zero();
  w_W_ = pose.has_velocity ? pose.w_WD : Vector3::Zero();
}

void DeviceVelocityEstimator::Update(const PoseSample& pose) {
  if (pose.has_velocity) {
    v_W_ = pose.v_WD;
    w_W_ = pose.w_WD;
  } else if (has_previous_) {
    const double dt = 1e-6 * static_cast<double>(pose.utime - previous_.utime);
    if (dt >= kMinStep && dt <= kMaxStep) {
      const Vector3 v_raw = (pose.p_WD - previous_.p_WD) / dt;
      const Vector3 w_raw = RotationVectorFromQuaternion(pose.q_WD * previous_.q_WD.conjugate()) / dt;
      const double alpha = 1.0 - std::exp(-2.0 * M_PI * cutoff_hz_ * dt);
      v_W_ += alpha * (v_raw - v_W_);
      w_W_ += alpha * (w_raw - w_W_);
    } else {
      // A gap or a clock jump: the difference means nothing.
      v_W_.setZero();
      w_W_.setZero();
    }
  }
  previous_ = pose;
  has_previous_ = true;
}

void DeviceVelocityEstimator::Stop() {
  v_W_.setZero();
  w_W_.setZero();
}

}  // namespace haptics
