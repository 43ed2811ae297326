// Scripted motions: they reach the requested points, stay smooth, fill the
// duration, and report impossible parameters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "probes/trajectory/input_error.h"
#include "probes/trajectory/motion_params.h"
#include "probes/trajectory/motion_scripts.h"

namespace probes {
namespace {

MotionParams Params(const std::string& script) {
  MotionParams p;
  p.script = script;
  p.centre = {0.1, -0.2, 0.05};
  p.amplitude = 0.02;
  p.depth = 0.004;
  p.speed = 0.02;
  p.duration = 12.0;
  p.approach = 0.01;
  p.hold = 0.3;
  ValidateMotionParams(&p);
  return p;
}

double MinZ(const Trajectory& t) {
  double z = t.front().p_WP[2];
  for (const PoseSample& s : t) z = std::min(z, s.p_WP[2]);
  return z;
}

// Peak speed and the largest difference between analytic and finite-difference velocity.
void CheckSmooth(const Trajectory& t, double speed) {
  double worst_mismatch = 0.0;
  for (size_t k = 1; k + 1 < t.size(); ++k) {
    const double dt = t[k + 1].t - t[k - 1].t;
    double v2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double fd = (t[k + 1].p_WP[i] - t[k - 1].p_WP[i]) / dt;
      worst_mismatch = std::max(worst_mismatch, std::abs(fd - t[k].v_WP[i]));
      v2 += t[k].v_WP[i] * t[k].v_WP[i];
    }
    // Minimum-jerk peak speed is 1.875 x the average.
    ASSERT_LE(std::sqrt(v2), 1.875 * speed * (1 + 1e-6)) << "at t = " << t[k].t;
  }
  EXPECT_LT(worst_mismatch, 1e-4);  // m/s: positions and velocities agree, no jumps
}

TEST(MotionScripts, PressGoesFromAmplitudeAboveToDepthBelow) {
  const MotionParams p = Params("approach_and_press");
  const Trajectory t = SampleMotion(p);
  ASSERT_EQ(t.size(), 12000u);
  EXPECT_DOUBLE_EQ(t.front().t, 0.0);
  EXPECT_NEAR(t.front().p_WP[2], 0.05 + 0.02, 1e-12);
  EXPECT_NEAR(MinZ(t), 0.05 - 0.004, 1e-9);
  EXPECT_NEAR(t.back().p_WP[2], 0.07, 1e-9);  // ends back at the top
  for (const PoseSample& s : t) {
    ASSERT_DOUBLE_EQ(s.p_WP[0], 0.1);
    ASSERT_TRUE(s.has_velocity);
  }
  CheckSmooth(t, p.speed);
}

TEST(MotionScripts, SlideStrokesAtDepth) {
  const MotionParams p = Params("slide");
  const Trajectory t = SampleMotion(p);
  double min_x = 1e9, max_x = -1e9;
  for (const PoseSample& s : t) {
    min_x = std::min(min_x, s.p_WP[0]);
    max_x = std::max(max_x, s.p_WP[0]);
  }
  EXPECT_NEAR(min_x, 0.08, 1e-9);
  EXPECT_NEAR(max_x, 0.12, 1e-9);
  EXPECT_NEAR(MinZ(t), 0.046, 1e-9);
  CheckSmooth(t, p.speed);
}

TEST(MotionScripts, StirCirclesAtRadius) {
  const MotionParams p = Params("stir");
  const Trajectory t = SampleMotion(p);
  double max_r = 0.0;
  for (const PoseSample& s : t) {
    max_r = std::max(max_r, std::hypot(s.p_WP[0] - 0.1, s.p_WP[1] + 0.2));
    if (s.p_WP[2] > 0.046 + 1e-9) {
      ASSERT_LT(std::hypot(s.p_WP[0] - 0.1, s.p_WP[1] + 0.2), 1e-9)
          << "leaves the axis above the stirring depth at t = " << s.t;
    }
  }
  EXPECT_NEAR(max_r, 0.02, 1e-9);
  CheckSmooth(t, p.speed);
}

TEST(MotionScripts, InsertPegWithWiggle) {
  MotionParams p = Params("insert_peg");
  p.amplitude = 0.001;
  const Trajectory t = SampleMotion(p);
  EXPECT_NEAR(MinZ(t), 0.046, 1e-9);
  EXPECT_NEAR(t.front().p_WP[2], 0.06, 1e-12);
  CheckSmooth(t, p.speed);
}

TEST(MotionScripts, TooShortDurationIsAnError) {
  MotionParams p = Params("stir");
  p.duration = 1.0;
  try {
    SampleMotion(p);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'duration' = 1"), std::string::npos) << e.what();
  }
}

TEST(MotionParams, ValidationNamesTheField) {
  MotionParams p;
  p.script = "stirr";
  EXPECT_THROW(ValidateMotionParams(&p), InputError);
  p.script = "slide";
  p.speed = -1.0;
  try {
    ValidateMotionParams(&p);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'speed'"), std::string::npos) << e.what();
  }
  p.speed = 0.01;
  p.orientation = {0.5, 0.0, 0.0, 0.0};
  EXPECT_THROW(ValidateMotionParams(&p), InputError);
}

}  // namespace
}  // namespace probes
