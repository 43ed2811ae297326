#pragma once
// Pose of the probe P in the scene object's frame S, with the absolute
// rotation matrix that box tests need. Pair queries run in S so that the
// scene's BVH is used as stored and only the probe's features are moved.
#include <algorithm>
#include <cmath>

#include "pd_core/geometry/pose.h"

namespace pd {

struct RelativePose {
  Matrix3 R_SP;
  Vector3 p_SP;      // origin of P in S (m)
  Matrix3 absR_SP;   // |R_SP| plus a tiny epsilon against round-off in box tests

  static RelativePose FromWorld(const Isometry3& X_WS, const Isometry3& X_WP) {
    RelativePose r;
    const Matrix3 R_WS = X_WS.linear();
    r.R_SP = R_WS.transpose() * X_WP.linear();
    r.p_SP = R_WS.transpose() * (X_WP.translation() - X_WS.translation());
    r.absR_SP = r.R_SP.cwiseAbs().array() + 1e-12;
    return r;
  }
  Vector3 operator*(const Vector3& p_PQ) const { return R_SP * p_PQ + p_SP; }
};

// Angle (rad) of the rotation taking R_a to R_b.
inline double RotationAngleBetween(const Matrix3& R_a, const Matrix3& R_b) {
  const Matrix3 dR = R_a.transpose() * R_b;
  return std::acos(std::clamp(0.5 * (dR.trace() - 1.0), -1.0, 1.0));
}

}  // namespace pd
