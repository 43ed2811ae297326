#pragma once
// Rigid poses. Frames are written into names: X_WA is the pose of frame A in
// world W, so p_W = X_WA * p_A. Positions are metres; quaternions are unit and
// written w, x, y, z.
#include <Eigen/Geometry>

namespace pd {

using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;
using Isometry3 = Eigen::Isometry3d;
using Quaternion = Eigen::Quaterniond;

// Builds X_WA from a position (m) and a quaternion (w, x, y, z). The
// quaternion is normalised; callers validate unit length beforehand when the
// input is untrusted.
inline Isometry3 MakePose(const Vector3& p_WA, double qw, double qx, double qy,
                          double qz) {
  Isometry3 X = Isometry3::Identity();
  X.linear() = Quaternion(qw, qx, qy, qz).normalized().toRotationMatrix();
  X.translation() = p_WA;
  return X;
}

// Applies a world-frame translation t_W to pose X_WA (the probe moved by t_W).
inline Isometry3 TranslatedPose(const Isometry3& X_WA, const Vector3& t_W) {
  Isometry3 X = X_WA;
  X.translation() += t_W;
  return X;
}

}  // namespace pd
