#include "haptics/tool/virtual_coupling.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "haptics/tool/rotation_vector.h"

namespace haptics {
namespace {

CouplingConfig Gains() {
  CouplingConfig g;
  g.k_translational = 1000.0;
  g.b_translational = 5.0;
  g.k_rotational = 0.5;
  g.b_rotational = 0.003;
  return g;
}

TEST(VirtualCoupling, PullsTheToolTowardTheDeviceAndPushesTheDeviceBack) {
  const VirtualCoupling coupling(Gains());
  RigidState device, tool;
  device.X_W.translation() = Vector3(0.0, 0.0, -0.002);  // 2 mm below the tool
  device.X_W.linear() = Eigen::AngleAxisd(0.1, Vector3::UnitZ()).toRotationMatrix();
  tool.v_W = Vector3(0.01, 0, 0);
  const Wrench on_tool = coupling.OnTool(device, tool);
  EXPECT_TRUE(on_tool.f_W.isApprox(Vector3(-0.05, 0, -2.0), 1e-12));  // k e + b (0 - v)
  EXPECT_TRUE(on_tool.tau_W.isApprox(Vector3(0, 0, 0.05), 1e-12));    // turns toward the device
  const Wrench on_device = coupling.OnDevice(device, tool);
  EXPECT_TRUE(on_device.f_W.isApprox(-on_tool.f_W, 1e-15));
  EXPECT_TRUE(on_device.tau_W.isApprox(-on_tool.tau_W, 1e-15));
}

TEST(VirtualCoupling, SaturatesTheSpringsKeepingDirection) {
  const VirtualCoupling coupling(Gains(), /*max_spring_force=*/12.0, /*max_spring_torque=*/0.2);
  RigidState device, tool;
  device.X_W.translation() = Vector3(0.03, 0.0, -0.04);  // 50 N unsaturated
  device.X_W.linear() = Eigen::AngleAxisd(1.0, Vector3::UnitY()).toRotationMatrix();
  const Wrench w = coupling.OnTool(device, tool);
  EXPECT_NEAR(w.f_W.norm(), 12.0, 1e-12);
  EXPECT_TRUE(w.f_W.normalized().isApprox(Vector3(0.6, 0, -0.8), 1e-12));
  EXPECT_NEAR(w.tau_W.norm(), 0.2, 1e-12);
  EXPECT_TRUE(w.tau_W.normalized().isApprox(Vector3::UnitY(), 1e-12));
}

// K and D must describe how the wrench changes as the tool moves.
TEST(VirtualCoupling, LinearizationMatchesFiniteDifferences) {
  for (double limit : {1e9, 1.0}) {  // linear and saturated springs
    const VirtualCoupling coupling(Gains(), limit, 1e9);
    RigidState device, tool;
    device.X_W.translation() = Vector3(0.003, -0.002, 0.001);
    device.X_W.linear() = Eigen::AngleAxisd(0.2, Vector3(1, 2, 3).normalized()).toRotationMatrix();
    tool.X_W.linear() = Eigen::AngleAxisd(0.05, Vector3::UnitX()).toRotationMatrix();
    const LinearizedWrench lw = coupling.Linearize(device, tool);
    const double eps = 1e-7;
    for (int j = 0; j < 6; ++j) {
      // Central differences: the tool moved by +-eps along coordinate j.
      Vector6 dw = Vector6::Zero();
      for (double sign : {1.0, -1.0}) {
        RigidState moved = tool;
        if (j < 3) {
          moved.X_W.translation()[j] += sign * eps;
        } else {
          moved.X_W.linear() =
              QuaternionFromRotationVector(sign * eps * Vector3::Unit(j - 3)).toRotationMatrix() *
              tool.X_W.linear();
        }
        const Wrench w = coupling.OnTool(device, moved);
        Vector6 w6;
        w6 << w.f_W, w.tau_W;
        dw += sign * w6 / (2.0 * eps);
      }
      // -K column j, to first order. For rotations K uses d(theta) = -d(angle),
      // exact at zero error and off by about |theta| / 2 = 10 % here.
      const double tol = j < 3 ? 1e-6 * lw.K.norm() : 0.15 * Gains().k_rotational;
      EXPECT_LT((dw + lw.K.col(j)).norm(), tol) << "limit " << limit << " column " << j;
    }
    EXPECT_TRUE(lw.K.isApprox(lw.K.transpose(), 1e-12));
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Matrix6>(lw.K).eigenvalues().minCoeff(), -1e-12);
  }
}

}  // namespace
}  // namespace haptics
