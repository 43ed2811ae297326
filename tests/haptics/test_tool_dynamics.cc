#include "haptics/tool/tool_dynamics.h"

#include <gtest/gtest.h>

#include <limits>

#include "haptics/tool/rotation_vector.h"

namespace haptics {
namespace {

constexpr double kDt = 1e-3;

// A spring to a fixed anchor (translation and rotation) as a LinearizedWrench.
LinearizedWrench AnchorSpring(const RigidState& s, const Vector3& anchor, double k, double b,
                              double k_r, double b_r) {
  LinearizedWrench w;
  w.w0.f_W = k * (anchor - s.X_W.translation()) - b * s.v_W;
  w.w0.tau_W = k_r * RotationError_W(s.X_W.linear(), Matrix3::Identity()) - b_r * s.w_W;
  w.K.topLeftCorner<3, 3>().diagonal().setConstant(k);
  w.K.bottomRightCorner<3, 3>().diagonal().setConstant(k_r);
  w.D.topLeftCorner<3, 3>().diagonal().setConstant(b);
  w.D.bottomRightCorner<3, 3>().diagonal().setConstant(b_r);
  return w;
}

TEST(ToolDynamics, FreeBodyKeepsItsMomentum) {
  ToolDynamics tool(0.1, 1e-4 * Matrix3::Identity());
  tool.Reset(Isometry3::Identity());
  LinearizedWrench push;
  push.w0.f_W = Vector3(1.0, 0, 0);  // 1 N for 1 ms on 0.1 kg: 0.01 m/s
  push.w0.tau_W = Vector3(0, 0, 1e-4);  // 1e-4 N·m for 1 ms on 1e-4: 1e-3 rad/s
  tool.Step(kDt, push);
  EXPECT_NEAR(tool.state().v_W.x(), 0.01, 1e-15);
  EXPECT_NEAR(tool.state().w_W.z(), 1e-3, 1e-15);
  const LinearizedWrench none;
  for (int i = 0; i < 999; ++i) tool.Step(kDt, none);
  EXPECT_NEAR(tool.state().v_W.x(), 0.01, 1e-15);
  EXPECT_NEAR(tool.state().X_W.translation().x(), 0.01, 1e-12);  // 1000 steps of 1e-5 m
  EXPECT_NEAR(tool.state().w_W.z(), 1e-3, 1e-15);
  EXPECT_NEAR(RotationVectorFromQuaternion(Quaternion(tool.state().X_W.linear())).z(), 1e-3, 1e-12);
}

TEST(ToolDynamics, GravityIsOffByDefaultAndAppliesWhenSet) {
  ToolDynamics off(0.1, 1e-4 * Matrix3::Identity());
  ToolDynamics on(0.1, 1e-4 * Matrix3::Identity(), Vector3(0, 0, -9.81));
  off.Reset(Isometry3::Identity());
  on.Reset(Isometry3::Identity());
  for (int i = 0; i < 100; ++i) {
    off.Step(kDt, LinearizedWrench{});
    on.Step(kDt, LinearizedWrench{});
  }
  EXPECT_EQ(off.state().v_W, Vector3::Zero());
  EXPECT_NEAR(on.state().v_W.z(), -0.981, 1e-12);
}

// A spring far too stiff for an explicit step (w h = 30) still loses energy
// every step: the implicit treatment is unconditionally stable.
TEST(ToolDynamics, ImplicitSpringIsStableAtAnyStiffness) {
  const double m = 0.01, k = 9e6, k_r = 100.0;
  const Matrix3 I = 1e-6 * Matrix3::Identity();
  ToolDynamics tool(m, I);
  Isometry3 X = Isometry3::Identity();
  X.translation() = Vector3(0.01, -0.02, 0.005);
  X.linear() = Eigen::AngleAxisd(0.5, Vector3(1, 1, 0).normalized()).toRotationMatrix();
  tool.Reset(X);
  auto energy = [&] {
    const RigidState& s = tool.state();
    const double theta = RotationError_W(s.X_W.linear(), Matrix3::Identity()).norm();
    return tool.KineticEnergy() + 0.5 * k * s.X_W.translation().squaredNorm() +
           0.5 * k_r * theta * theta;
  };
  double previous = energy();
  for (int i = 0; i < 2000; ++i) {
    tool.Step(kDt, AnchorSpring(tool.state(), Vector3::Zero(), k, 0.0, k_r, 0.0));
    const double e = energy();
    ASSERT_TRUE(std::isfinite(e));
    EXPECT_LE(e, previous * (1.0 + 1e-9)) << "step " << i;
    previous = e;
  }
  EXPECT_LT(tool.state().X_W.translation().norm(), 1e-6);
}

TEST(ToolDynamics, DampedSpringSettlesAtTheAnchor) {
  ToolDynamics tool(0.02, 1e-5 * Matrix3::Identity());
  Isometry3 X = Isometry3::Identity();
  X.linear() = Eigen::AngleAxisd(0.3, Vector3::UnitX()).toRotationMatrix();
  tool.Reset(X);
  const Vector3 anchor(0.01, 0.0, -0.02);
  for (int i = 0; i < 3000; ++i)
    tool.Step(kDt, AnchorSpring(tool.state(), anchor, 1000.0, 5.0, 0.5, 0.003));
  EXPECT_LT((tool.state().X_W.translation() - anchor).norm(), 1e-9);
  EXPECT_LT(RotationError_W(tool.state().X_W.linear(), Matrix3::Identity()).norm(), 1e-9);
  EXPECT_LT(tool.state().v_W.norm(), 1e-8);
}

TEST(ToolDynamics, NonFiniteWrenchStopsTheToolInsteadOfPoisoningIt) {
  ToolDynamics tool(0.02, 1e-5 * Matrix3::Identity());
  tool.Reset(Isometry3::Identity());
  LinearizedWrench bad;
  bad.w0.f_W = Vector3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  tool.Step(kDt, bad);
  EXPECT_TRUE(tool.state().X_W.matrix().allFinite());
  EXPECT_TRUE(tool.state().v_W.allFinite());
  EXPECT_EQ(tool.nonfinite_steps(), 1);
}

}  // namespace
}  // namespace haptics
