#pragma once
// Velocity of the device handle for the coupling damper. A pose that carries
// a measured velocity is used as is; otherwise successive accepted poses are
// differenced over their sender timestamps (robust to poses arriving in
// bursts) and low-pass filtered, since differencing amplifies sensor noise.
#include <cstdint>

#include "haptics/io/pose_sample.h"
#include "haptics/tool/spatial.h"

namespace haptics {

class DeviceVelocityEstimator {
 public:
  // Cut-off of the first-order low-pass (Hz), > 0.
  explicit DeviceVelocityEstimator(double cutoff_hz);

  // Starts over at `pose` (zero velocity unless measured).
  void Reset(const PoseSample& pose);
  // A newly accepted pose (quaternion unit).
  void Update(const PoseSample& pose);
  // Zero velocity (e.g. input went stale: the handle's motion is unknown).
  void Stop();

  const Vector3& v_W() const { return v_W_; }  // m/s
  const Vector3& w_W() const { return w_W_; }  // rad/s

 private:
  double cutoff_hz_;
  bool has_previous_ = false;
  PoseSample previous_;
  Vector3 v_W_ = Vector3::Zero();
  Vector3 w_W_ = Vector3::Zero();
};

}  // namespace haptics
