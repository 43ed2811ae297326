#include "pd_core/geometry/parse_pose_line.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace pd {
namespace {

using Kind = PoseLine::Kind;

TEST(ParsePoseLine, ReadsPositionAndQuaternionWFirst) {
  // 90 degrees about z: (w, x, y, z) = (cos 45, 0, 0, sin 45).
  const double c = std::sqrt(0.5);
  const PoseLine line = ParsePoseLine("0.1 -0.2 3e-1 " + std::to_string(c) + " 0 0 " +
                                      std::to_string(c));
  ASSERT_EQ(line.kind, Kind::kPose) << line.error;
  EXPECT_TRUE(line.X_WP.translation().isApprox(Vector3(0.1, -0.2, 0.3)));
  // p_W = X_WP * p_P: the probe's x axis maps to world y.
  const Vector3 p_W = line.X_WP * Vector3(1, 0, 0);
  EXPECT_NEAR((p_W - Vector3(0.1, 0.8, 0.3)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((line.X_WP.linear().transpose() * line.X_WP.linear() - Matrix3::Identity()).norm(),
              0.0, 1e-12);
}

TEST(ParsePoseLine, AcceptsTabsCarriageReturnAndSurroundingBlanks) {
  const PoseLine line = ParsePoseLine("  1\t2  3 1 0 0 0 \r");
  ASSERT_EQ(line.kind, Kind::kPose) << line.error;
  EXPECT_EQ(line.X_WP.translation(), Vector3(1, 2, 3));
  EXPECT_TRUE(line.X_WP.linear().isIdentity());
}

TEST(ParsePoseLine, NormalisesNearlyUnitQuaternions) {
  const PoseLine line = ParsePoseLine("0 0 0 1.0009 0 0 0");
  ASSERT_EQ(line.kind, Kind::kPose) << line.error;
  EXPECT_TRUE(line.X_WP.linear().isApprox(Matrix3::Identity(), 1e-14));
}

TEST(ParsePoseLine, SkipsBlankAndCommentLines) {
  for (const char* text : {"", "   ", "\t\r", "# x y z qw qx qy qz", "   #1 2 3 1 0 0 0"}) {
    const PoseLine line = ParsePoseLine(text);
    EXPECT_EQ(line.kind, Kind::kSkip) << "'" << text << "'";
    EXPECT_TRUE(line.error.empty());
  }
}

// The line must be refused with an error mentioning `what`.
void ExpectError(const std::string& text, const std::string& what) {
  const PoseLine line = ParsePoseLine(text);
  EXPECT_EQ(line.kind, Kind::kError) << "'" << text << "'";
  EXPECT_NE(line.error.find(what), std::string::npos)
      << "'" << text << "' gave '" << line.error << "', expected mention of '" << what << "'";
}

TEST(ParsePoseLine, RefusesWrongFieldCounts) {
  ExpectError("1 2 3", "got 3 fields");
  ExpectError("0 0 0 1 0 0", "got 6 fields");
  ExpectError("0 0 0 1 0 0 0 0", "got 8 fields");
  ExpectError("0 0 0 1 0 0 0 # trailing comment", "got 10 fields");
}

TEST(ParsePoseLine, RefusesNonNumbers) {
  ExpectError("0 0 0 1 0 0 x", "qz = 'x' is not a number");
  ExpectError("a 0 0 1 0 0 0", "x = 'a' is not a number");
  ExpectError("0 0 0.5m 1 0 0 0", "z = '0.5m' is not a number");
  ExpectError("0 0 0 1,0 0 0 0", "qw = '1,0' is not a number");
}

TEST(ParsePoseLine, RefusesNonFiniteNumbers) {
  ExpectError("nan 0 0 1 0 0 0", "x = 'nan' is not finite");
  ExpectError("0 inf 0 1 0 0 0", "y = 'inf' is not finite");
  ExpectError("0 0 -1e999 1 0 0 0", "z = '-1e999' is not finite");
  ExpectError("0 0 0 NaN 0 0 0", "qw = 'NaN' is not finite");
}

TEST(ParsePoseLine, RefusesNonUnitQuaternions) {
  ExpectError("0 0 0 0 0 0 0", "norm 0");
  ExpectError("0 0 0 1 1 0 0", "norm 1.414");
  ExpectError("0 0 0 1.002 0 0 0", "not within 0.001 of 1");
  ExpectError("0 0 0 0.998 0 0 0", "norm");
}

}  // namespace
}  // namespace pd
