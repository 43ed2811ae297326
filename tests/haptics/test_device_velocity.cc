#include "haptics/tool/device_velocity.h"

#include <gtest/gtest.h>

#include "haptics/tool/rotation_vector.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

// A handle moving at v and turning at w, sampled every `dt_us` of sender time.
PoseSample Sample(int64_t utime, const Vector3& v, const Vector3& w) {
  const double t = 1e-6 * static_cast<double>(utime);
  PoseSample s = test::MakePose(utime / 1000, v * t, QuaternionFromRotationVector(w * t));
  s.utime = utime;
  return s;
}

TEST(DeviceVelocity, DifferencesOverSenderTimeAndFilters) {
  const Vector3 v(0.1, -0.05, 0.02), w(0.0, 0.5, -0.3);
  DeviceVelocityEstimator estimator(100.0);
  estimator.Reset(Sample(0, v, w));
  EXPECT_EQ(estimator.v_W(), Vector3::Zero());
  // Irregular arrival: steps of 1 and 2 ms (a pose dropped now and then).
  int64_t utime = 0;
  for (int i = 0; i < 300; ++i) {
    utime += (i % 3 == 0) ? 2000 : 1000;
    estimator.Update(Sample(utime, v, w));
  }
  EXPECT_LT((estimator.v_W() - v).norm(), 1e-9);
  EXPECT_LT((estimator.w_W() - w).norm(), 1e-9);
  // The low-pass: one step after a velocity change it has not caught up.
  utime += 1000;
  PoseSample jump = Sample(utime, v, w);
  jump.p_WD += Vector3(0.001, 0, 0);  // 1 m/s extra for one sample
  estimator.Update(jump);
  const double alpha = 1.0 - std::exp(-2.0 * M_PI * 100.0 * 1e-3);
  EXPECT_NEAR(estimator.v_W().x() - v.x(), alpha * 1.0, 1e-9);
}

TEST(DeviceVelocity, MeasuredVelocityIsUsedAsIs) {
  DeviceVelocityEstimator estimator(100.0);
  PoseSample s = test::MakePose(1, Vector3::Zero());
  s.has_velocity = true;
  s.v_WD = Vector3(0.3, 0, 0);
  s.w_WD = Vector3(0, 0, 2.0);
  estimator.Reset(s);
  EXPECT_EQ(estimator.v_W(), s.v_WD);
  s.v_WD = Vector3(0, 0.2, 0);
  estimator.Update(s);
  EXPECT_EQ(estimator.v_W(), s.v_WD);
  EXPECT_EQ(estimator.w_W(), s.w_WD);
}

TEST(DeviceVelocity, GapsAndStopsGiveZero) {
  DeviceVelocityEstimator estimator(100.0);
  estimator.Reset(Sample(0, Vector3(0.1, 0, 0), Vector3::Zero()));
  for (int64_t u = 1000; u <= 100000; u += 1000) estimator.Update(Sample(u, Vector3(0.1, 0, 0), Vector3::Zero()));
  ASSERT_GT(estimator.v_W().x(), 0.09);
  // 0.5 s without a pose: the difference says nothing about the velocity.
  estimator.Update(Sample(600000, Vector3(0.1, 0, 0), Vector3::Zero()));
  EXPECT_EQ(estimator.v_W(), Vector3::Zero());
  // A clock going backwards likewise.
  estimator.Update(Sample(500000, Vector3(0.1, 0, 0), Vector3::Zero()));
  EXPECT_EQ(estimator.v_W(), Vector3::Zero());
  estimator.Update(Sample(501000, Vector3(0.1, 0, 0), Vector3::Zero()));
  EXPECT_GT(estimator.v_W().x(), 0.0);
  estimator.Stop();
  EXPECT_EQ(estimator.v_W(), Vector3::Zero());
  EXPECT_EQ(estimator.w_W(), Vector3::Zero());
}

}  // namespace
}  // namespace haptics
