#include "haptics/tool/virtual_coupling.h"

#include "haptics/tool/rotation_vector.h"

namespace haptics {
namespace {

// A spring k e saturating at `limit`: its force and its stiffness with
// respect to the tool's motion (e shrinks as the tool moves along it).
void SaturatedSpring(double k, const Vector3& e, double limit, Vector3* force, Matrix3* stiffness) {
  const double e_norm = e.norm();
  if (k * e_norm <= limit) {
    *force = k * e;
    *stiffness = k * Matrix3::Identity();
    return;
  }
  const Vector3 u = e / e_norm;
  *force = limit * u;
  *stiffness = (limit / e_norm) * (Matrix3::Identity() - u * u.transpose());
}

}  // namespace

VirtualCoupling::VirtualCoupling(const CouplingConfig& gains, double max_spring_force,
                                 double max_spring_torque)
    : gains_(gains), max_force_(max_spring_force), max_torque_(max_spring_torque) {}

LinearizedWrench VirtualCoupling::Linearize(const RigidState& device, const RigidState& tool) const {
  const Vector3 e_W = device.X_W.translation() - tool.X_W.translation();
  const Vector3 theta_W = RotationError_W(tool.X_W.linear(), device.X_W.linear());
  LinearizedWrench lw;
  Vector3 f_spring, tau_spring;
  Matrix3 K_t, K_r;
  SaturatedSpring(gains_.k_translational, e_W, max_force_, &f_spring, &K_t);
  SaturatedSpring(gains_.k_rotational, theta_W, max_torque_, &tau_spring, &K_r);
  lw.w0.f_W = f_spring + gains_.b_translational * (device.v_W - tool.v_W);
  lw.w0.tau_W = tau_spring + gains_.b_rotational * (device.w_W - tool.w_W);
  // Turning the tool by dtheta shrinks theta_W by dtheta (to first order).
  lw.K.topLeftCorner<3, 3>() = K_t;
  lw.K.bottomRightCorner<3, 3>() = K_r;
  lw.D.topLeftCorner<3, 3>().diagonal().setConstant(gains_.b_translational);
  lw.D.bottomRightCorner<3, 3>().diagonal().setConstant(gains_.b_rotational);
  return lw;
}

Wrench VirtualCoupling::OnTool(const RigidState& device, const RigidState& tool) const {
  return Linearize(device, tool).w0;
}

Wrench VirtualCoupling::OnDevice(const RigidState& device, const RigidState& tool) const {
  const Wrench on_tool = OnTool(device, tool);
  return {-on_tool.f_W, -on_tool.tau_W};
}

double VirtualCoupling::PotentialEnergy(const RigidState& device, const RigidState& tool) const {
  const Vector3 e_W = device.X_W.translation() - tool.X_W.translation();
  const Vector3 theta_W = RotationError_W(tool.X_W.linear(), device.X_W.linear());
  return 0.5 * gains_.k_translational * e_W.squaredNorm() +
         0.5 * gains_.k_rotational * theta_W.squaredNorm();
}

}  // namespace haptics
