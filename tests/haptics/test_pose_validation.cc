#include "haptics/io/pose_validation.h"

#include <gtest/gtest.h>

#include <limits>

#include "haptics_test_util.h"

namespace haptics {
namespace {

using test::MakePose;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

PoseValidator MakeValidator() {
  return PoseValidator(Vector3(-0.1, -0.1, -0.07), Vector3(0.1, 0.1, 0.07));
}

TEST(PoseValidation, AcceptsGoodPosesAndNormalisesTheQuaternion) {
  PoseValidator v = MakeValidator();
  PoseSample p = MakePose(1, Vector3(0.01, 0.02, 0.03), Quaternion(1.0005, 0, 0, 0));
  EXPECT_TRUE(v.Accept(p));
  EXPECT_TRUE(v.has_good());
  EXPECT_NEAR(v.last_good().q_WD.norm(), 1.0, 1e-15);
  EXPECT_EQ(v.accepted(), 1);
  EXPECT_EQ(v.rejections().total(), 0);
}

TEST(PoseValidation, RejectsAndCountsEachReasonKeepingTheLastGoodPose) {
  PoseValidator v = MakeValidator();
  ASSERT_TRUE(v.Accept(MakePose(1, Vector3(0.01, 0, 0))));

  PoseSample nan_p = MakePose(2, Vector3(kNaN, 0, 0));
  PoseSample inf_q = MakePose(3, Vector3::Zero(), Quaternion(kInf, 0, 0, 0));
  PoseSample nan_v = MakePose(4, Vector3::Zero());
  nan_v.has_velocity = true;
  nan_v.w_WD = Vector3(0, kNaN, 0);
  PoseSample long_q = MakePose(5, Vector3::Zero(), Quaternion(1.002, 0, 0, 0));
  PoseSample short_q = MakePose(6, Vector3::Zero(), Quaternion(0.5, 0.5, 0.5, 0.49));
  PoseSample zero_q = MakePose(7, Vector3::Zero(), Quaternion(0, 0, 0, 0));
  PoseSample outside_x = MakePose(8, Vector3(0.1001, 0, 0));
  PoseSample outside_z = MakePose(9, Vector3(0, 0, -0.5));

  EXPECT_EQ(v.Check(nan_p), PoseRejection::kNonFinite);
  EXPECT_EQ(v.Check(inf_q), PoseRejection::kNonFinite);
  EXPECT_EQ(v.Check(nan_v), PoseRejection::kNonFinite);
  EXPECT_EQ(v.Check(long_q), PoseRejection::kBadQuaternion);
  EXPECT_EQ(v.Check(short_q), PoseRejection::kBadQuaternion);
  EXPECT_EQ(v.Check(zero_q), PoseRejection::kBadQuaternion);
  EXPECT_EQ(v.Check(outside_x), PoseRejection::kOutsideWorkspace);
  EXPECT_EQ(v.Check(outside_z), PoseRejection::kOutsideWorkspace);

  for (const PoseSample* p : {&nan_p, &inf_q, &nan_v, &long_q, &short_q, &zero_q, &outside_x, &outside_z})
    EXPECT_FALSE(v.Accept(*p)) << p->seq;
  EXPECT_EQ(v.rejections().non_finite, 3);
  EXPECT_EQ(v.rejections().bad_quaternion, 3);
  EXPECT_EQ(v.rejections().outside_workspace, 2);
  EXPECT_EQ(v.rejections().total(), 8);
  EXPECT_EQ(v.accepted(), 1);
  EXPECT_EQ(v.last_good().seq, 1);
  EXPECT_EQ(v.last_good().p_WD, Vector3(0.01, 0, 0));
}

TEST(PoseValidation, VelocityIsIgnoredWhenNotMeasured) {
  PoseValidator v = MakeValidator();
  PoseSample p = MakePose(1, Vector3::Zero());
  p.has_velocity = false;
  p.v_WD = Vector3(kNaN, 0, 0);  // garbage in an unused field
  EXPECT_EQ(v.Check(p), PoseRejection::kNone);
}

}  // namespace
}  // namespace haptics
