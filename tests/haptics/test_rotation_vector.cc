#include "haptics/tool/rotation_vector.h"

#include <gtest/gtest.h>

namespace haptics {
namespace {

TEST(RotationVector, RoundTripsAndTakesTheShortWay) {
  const Vector3 axis = Vector3(1, -2, 0.5).normalized();
  for (double angle : {0.0, 1e-9, 1e-4, 0.3, 2.0, 3.1}) {
    const Vector3 theta = angle * axis;
    const Quaternion q = QuaternionFromRotationVector(theta);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_TRUE(RotationVectorFromQuaternion(q).isApprox(theta, 1e-12) ||
                theta.norm() < 1e-12)
        << angle;
    // -q is the same rotation.
    Quaternion minus_q(-q.w(), -q.x(), -q.y(), -q.z());
    EXPECT_LT((RotationVectorFromQuaternion(minus_q) - theta).norm(), 1e-12) << angle;
    EXPECT_TRUE(q.toRotationMatrix().isApprox(
        Eigen::AngleAxisd(angle, axis).toRotationMatrix(), 1e-12));
  }
}

TEST(RotationVector, ErrorTurnsTheFirstOrientationIntoTheSecond) {
  const Matrix3 R_WA = Eigen::AngleAxisd(0.4, Vector3(0, 1, 1).normalized()).toRotationMatrix();
  const Matrix3 R_WB = Eigen::AngleAxisd(0.25, Vector3::UnitZ()).toRotationMatrix() * R_WA;
  const Vector3 theta = RotationError_W(R_WA, R_WB);
  EXPECT_TRUE(theta.isApprox(0.25 * Vector3::UnitZ(), 1e-12));
}

}  // namespace
}  // namespace haptics
