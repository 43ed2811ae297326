#pragma once
// Rotation vectors (axis times angle, rad): the quaternion log and exp used
// for rotational errors and for integrating angular velocity.
#include <cmath>

#include "haptics/tool/spatial.h"

namespace haptics {

// The rotation vector of a unit quaternion, angle in [0, pi] (the short way
// round: q and -q give the same answer).
inline Vector3 RotationVectorFromQuaternion(const Quaternion& q) {
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const Vector3 v = sign * q.vec();
  const double w = sign * q.w();
  const double s = v.norm();
  // Near zero the angle is 2|v| to third order; avoids 0/0.
  if (s < 1e-12) return 2.0 * v;
  return (2.0 * std::atan2(s, w) / s) * v;
}

// The unit quaternion rotating by |theta| about theta / |theta|.
inline Quaternion QuaternionFromRotationVector(const Vector3& theta) {
  const double angle = theta.norm();
  if (angle < 1e-12) return Quaternion(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()).normalized();
  const double half = 0.5 * angle;
  const Vector3 v = (std::sin(half) / angle) * theta;
  return Quaternion(std::cos(half), v.x(), v.y(), v.z());
}

// Rotation vector, in W, that turns R_WA into R_WB: R_WB = exp(theta) R_WA.
inline Vector3 RotationError_W(const Matrix3& R_WA, const Matrix3& R_WB) {
  return RotationVectorFromQuaternion(Quaternion(Matrix3(R_WB * R_WA.transpose())));
}

}  // namespace haptics
