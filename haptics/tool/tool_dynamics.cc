#include "haptics/tool/tool_dynamics.h"

#include <Eigen/Cholesky>
#include <stdexcept>

#include "haptics/tool/rotation_vector.h"

namespace haptics {

ToolDynamics::ToolDynamics(double mass, const Matrix3& I_T, const Vector3& gravity_W)
    : mass_(mass), I_T_(I_T), gravity_W_(gravity_W) {
  if (!(mass > 0.0) || !std::isfinite(mass)) throw std::invalid_argument("ToolDynamics: mass must be > 0");
  if (!I_T.allFinite() || I_T.llt().info() != Eigen::Success)
    throw std::invalid_argument("ToolDynamics: inertia must be positive definite");
}

void ToolDynamics::Reset(const Isometry3& X_WT) {
  q_WT_ = Quaternion(X_WT.linear()).normalized();
  state_.X_W = Isometry3::Identity();
  state_.X_W.linear() = q_WT_.toRotationMatrix();
  state_.X_W.translation() = X_WT.translation();
  state_.v_W.setZero();
  state_.w_W.setZero();
}

Matrix3 ToolDynamics::I_W() const {
  const Matrix3 R = state_.X_W.linear();
  return R * I_T_ * R.transpose();
}

double ToolDynamics::KineticEnergy() const {
  return 0.5 * mass_ * state_.v_W.squaredNorm() + 0.5 * state_.w_W.dot(I_W() * state_.w_W);
}

void ToolDynamics::Step(double h, const LinearizedWrench& wrench) {
  const Matrix3 I_W = this->I_W();
  Matrix6 M = Matrix6::Zero();
  M.topLeftCorner<3, 3>() = mass_ * Matrix3::Identity();
  M.bottomRightCorner<3, 3>() = I_W;

  Vector6 V;
  V << state_.v_W, state_.w_W;
  Vector6 w0;
  w0 << wrench.w0.f_W + mass_ * gravity_W_,
      wrench.w0.tau_W - state_.w_W.cross(I_W * state_.w_W);

  const Matrix6 MD = M + h * wrench.D;
  const Matrix6 A = MD + (h * h) * wrench.K;
  const Vector6 b = MD * V + h * w0;
  // A is symmetric positive definite (M is, D and K are semi-definite).
  const Vector6 V_next = Eigen::LDLT<Matrix6>(A).solve(b);
  if (!V_next.allFinite()) {
    // Never let a bad input poison the state: stop the tool where it is.
    ++nonfinite_steps_;
    state_.v_W.setZero();
    state_.w_W.setZero();
    return;
  }
  state_.v_W = V_next.head<3>();
  state_.w_W = V_next.tail<3>();
  state_.X_W.translation() += h * state_.v_W;
  q_WT_ = (QuaternionFromRotationVector(h * state_.w_W) * q_WT_).normalized();
  state_.X_W.linear() = q_WT_.toRotationMatrix();
}

}  // namespace haptics
