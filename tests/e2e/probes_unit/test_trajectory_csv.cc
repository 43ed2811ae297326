// Trajectory CSV parser: accepted input, and errors that name file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "probes/trajectory/input_error.h"
#include "probes/trajectory/trajectory_csv.h"

namespace probes {
namespace {

Trajectory Parse(const std::string& text) {
  std::istringstream in(text);
  return ParseTrajectoryCsv(in, "traj.csv");
}

// The InputError message for `text`; fails the test if parsing succeeds.
std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

TEST(TrajectoryCsv, ParsesSamplesSkippingBlankAndCommentLines) {
  const Trajectory t = Parse(
      "# made by hand\n"
      "time,x,y,z,qw,qx,qy,qz\r\n"
      "0.0, 0.1, 0.2, 0.3, 1, 0, 0, 0\r\n"
      "\n"
      "0.001,0.1,0.2,0.29,0,0,0,1.0005\n");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0].t, 0.0);
  EXPECT_DOUBLE_EQ(t[0].p_WP[2], 0.3);
  EXPECT_DOUBLE_EQ(t[1].t, 0.001);
  EXPECT_DOUBLE_EQ(t[1].p_WP[2], 0.29);
  EXPECT_DOUBLE_EQ(t[1].q_WP[3], 1.0);  // normalised
  EXPECT_FALSE(t[1].has_velocity);
}

TEST(TrajectoryCsv, NormalisesNearlyUnitQuaternions) {
  const Trajectory t = Parse("time,x,y,z,qw,qx,qy,qz\n0,0,0,0,0.7072,0,0,0.7072\n");
  const Quat& q = t[0].q_WP;
  EXPECT_NEAR(q[0] * q[0] + q[3] * q[3], 1.0, 1e-12);
}

TEST(TrajectoryCsv, RejectsEmptyFile) {
  EXPECT_NE(ErrorOf("").find("traj.csv: empty file"), std::string::npos);
  EXPECT_NE(ErrorOf("\n# only a comment\n").find("traj.csv: empty file"), std::string::npos);
}

TEST(TrajectoryCsv, RejectsWrongHeaderNamingLine) {
  const std::string e = ErrorOf("\ntime,x,y,z,qx,qy,qz,qw\n0,0,0,0,1,0,0,0\n");
  EXPECT_NE(e.find("traj.csv:2: header must be 'time,x,y,z,qw,qx,qy,qz'"), std::string::npos) << e;
}

TEST(TrajectoryCsv, RejectsHeaderOnly) {
  EXPECT_NE(ErrorOf("time,x,y,z,qw,qx,qy,qz\n").find("no samples"), std::string::npos);
}

TEST(TrajectoryCsv, RejectsWrongFieldCountNamingLine) {
  const std::string e = ErrorOf(
      "time,x,y,z,qw,qx,qy,qz\n"
      "0,0,0,0,1,0,0,0\n"
      "0.001,0,0,0,1,0,0\n");
  EXPECT_NE(e.find("traj.csv:3: expected 8 fields"), std::string::npos) << e;
  EXPECT_NE(e.find("got 7"), std::string::npos) << e;
}

TEST(TrajectoryCsv, RejectsNonNumberNamingLineFieldAndValue) {
  const std::string e = ErrorOf(
      "time,x,y,z,qw,qx,qy,qz\n"
      "0,0,0,0,1,0,0,0\n"
      "0.001,0,0,0,1,abc,0,0\n");
  EXPECT_NE(e.find("traj.csv:3: field 'qx': 'abc' is not a number"), std::string::npos) << e;
}

TEST(TrajectoryCsv, RejectsTrailingGarbageAndEmptyField) {
  EXPECT_NE(ErrorOf("time,x,y,z,qw,qx,qy,qz\n0,0.1m,0,0,1,0,0,0\n")
                .find("traj.csv:2: field 'x': '0.1m' is not a number"),
            std::string::npos);
  EXPECT_NE(ErrorOf("time,x,y,z,qw,qx,qy,qz\n0,0,,0,1,0,0,0\n").find("traj.csv:2: field 'y' is empty"),
            std::string::npos);
}

TEST(TrajectoryCsv, RejectsNonFiniteValues) {
  const std::string e = ErrorOf("time,x,y,z,qw,qx,qy,qz\n0,0,0,nan,1,0,0,0\n");
  EXPECT_NE(e.find("traj.csv:2: field 'z': 'nan' is not finite"), std::string::npos) << e;
  EXPECT_NE(ErrorOf("time,x,y,z,qw,qx,qy,qz\ninf,0,0,0,1,0,0,0\n").find("'time': 'inf' is not finite"),
            std::string::npos);
}

TEST(TrajectoryCsv, AcceptsSubnormalsRejectsOverflowAndHex) {
  // Another tool may well write 1e-310 for "zero"; 1e999 overflows to inf.
  const Trajectory t = Parse("time,x,y,z,qw,qx,qy,qz\n0,1e-310,-2.5e-320,0,1,0,0,0\n");
  EXPECT_GT(t[0].p_WP[0], 0.0);
  EXPECT_LT(t[0].p_WP[0], 1e-300);
  EXPECT_NE(ErrorOf("time,x,y,z,qw,qx,qy,qz\n0,1e999,0,0,1,0,0,0\n").find("'1e999' is not finite"),
            std::string::npos);
  EXPECT_NE(ErrorOf("time,x,y,z,qw,qx,qy,qz\n0,0x10,0,0,1,0,0,0\n").find("'0x10' is not a number"),
            std::string::npos);
}

TEST(TrajectoryCsv, RejectsTimeThatDoesNotIncrease) {
  const std::string e = ErrorOf(
      "time,x,y,z,qw,qx,qy,qz\n"
      "0.5,0,0,0,1,0,0,0\n"
      "# comment line still counts\n"
      "0.5,0,0,0,1,0,0,0\n");
  EXPECT_NE(e.find("traj.csv:4: field 'time'"), std::string::npos) << e;
  EXPECT_NE(e.find("on line 2"), std::string::npos) << e;
}

TEST(TrajectoryCsv, RejectsNonUnitQuaternion) {
  const std::string e = ErrorOf("time,x,y,z,qw,qx,qy,qz\n0,0,0,0,0.5,0,0,0\n");
  EXPECT_NE(e.find("traj.csv:2: quaternion"), std::string::npos) << e;
  EXPECT_NE(ErrorOf("time,x,y,z,qw,qx,qy,qz\n0,0,0,0,0,0,0,0\n").find("traj.csv:2: quaternion"),
            std::string::npos);
}

TEST(TrajectoryCsv, MissingFileNamesPath) {
  try {
    ReadTrajectoryCsv("/nonexistent/dir/traj.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/traj.csv: cannot open"), std::string::npos);
  }
}

TEST(TrajectoryCsv, WriteThenParseRoundTrips) {
  Trajectory original(3);
  for (int i = 0; i < 3; ++i) {
    original[i].t = 0.001 * i;
    original[i].p_WP = {0.0123456789 * i, -0.5, 1e-7 * i};
    original[i].q_WP = {std::cos(0.1 * i), 0.0, 0.0, std::sin(0.1 * i)};
  }
  std::stringstream buffer;
  WriteTrajectoryCsv(buffer, original);
  const Trajectory parsed = ParseTrajectoryCsv(buffer, "buffer");
  ASSERT_EQ(parsed.size(), original.size());
  for (size_t i = 0; i < parsed.size(); ++i) {
    EXPECT_NEAR(parsed[i].t, original[i].t, 1e-9);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(parsed[i].p_WP[k], original[i].p_WP[k], 1e-9);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(parsed[i].q_WP[k], original[i].q_WP[k], 1e-8);
  }
}

}  // namespace
}  // namespace probes
