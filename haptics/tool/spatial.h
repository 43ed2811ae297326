#pragma once
// Small spatial types shared by the haptics code. Frames are written into
// names: X_WT is the pose of tool frame T in world W, p_WQ a point, v_WT and
// w_WT the translational and angular velocity of T in W, f_W a force in W.
// SI units: m, kg, s, N, N·m, rad. 6-vectors are ordered [linear; angular].
#include <Eigen/Core>

#include "pd_core/geometry/pose.h"

namespace haptics {

using pd::Isometry3;
using pd::Matrix3;
using pd::Quaternion;
using pd::Vector3;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// A force and a torque about a stated reference point, both in W.
struct Wrench {
  Vector3 f_W = Vector3::Zero();    // N
  Vector3 tau_W = Vector3::Zero();  // N·m
  bool AllFinite() const { return f_W.allFinite() && tau_W.allFinite(); }
};

// A wrench as a function of the body's motion over the next step, for an
// implicit integrator: wrench(x + dx, V') ~= w0 - K dx - D (V' - V), where w0
// is the wrench at the current pose and velocity V, dx = [dp; dtheta] the
// small displacement of the step and V = [v; w]. K (N/m, N, N·m/rad blocks) and
// D (N·s/m, N·m·s/rad blocks) are symmetric positive semi-definite.
struct LinearizedWrench {
  Wrench w0;
  Matrix6 K = Matrix6::Zero();
  Matrix6 D = Matrix6::Zero();

  void SetZero() {
    w0 = Wrench{};
    K.setZero();
    D.setZero();
  }
  LinearizedWrench& operator+=(const LinearizedWrench& other) {
    w0.f_W += other.w0.f_W;
    w0.tau_W += other.w0.tau_W;
    K += other.K;
    D += other.D;
    return *this;
  }
};

// Pose and velocity of a rigid body: the simulated tool or the device handle.
struct RigidState {
  Isometry3 X_W = Isometry3::Identity();  // pose of the body frame in W
  Vector3 v_W = Vector3::Zero();          // velocity of the frame origin (m/s)
  Vector3 w_W = Vector3::Zero();          // angular velocity (rad/s)
};

}  // namespace haptics
