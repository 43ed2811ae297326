#include "bench/cases/haptic_paths.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

namespace pd_bench {
namespace {

using pd::Isometry3;
using pd::Vector3;

constexpr double kLift = 1e-3;             // m, lift-off height
constexpr double kLiftDuration = 0.025;    // s
constexpr double kMaxRadialSpeed = 0.2;    // m/s, how fast the hand follows the surface
constexpr int kBisections = 18;
constexpr double kGapScan = 0.5e-3;        // m, radial scan for the gap under an overhang

Isometry3 ToolPose(const BenchPair& pair, const pd::Matrix3& R, const Vector3& c_W) {
  Isometry3 X = Isometry3::Identity();
  X.linear() = R;
  X.translation() = c_W - R * pair.probe->model->center();
  return X;
}

}  // namespace

std::vector<HapticPairSpec> DefaultHapticPairs() {
  return {
      {"knot1_camel", "knot1.off", "camel.off", 0.1, 20.0, 1.5e-3, true},
      {"cow_armadillo", "cow.off", "armadillo.off", 0.2, 30.0, 3e-3, true},
      {"knot1_bunny", "knot1.off", "bunny00.off", 0.1, 20.0, 1.5e-3, false},
      {"bull_bunny", "bull.off", "bunny00.off", 0.05, 10.0, 0.5e-3, false},
      {"fandisk_elephant", "fandisk.off", "refined_elephant.off", 0.15, 25.0, 2e-3, false},
  };
}

HapticPath MakeHapticPath(const BenchPair& pair, const HapticPairSpec& spec, int steps,
                          uint64_t seed) {
  HapticPath out;
  std::ostringstream d;
  d << "tool r " << kHapticToolRadius * 100 << " cm over object r " << kHapticObjectRadius * 100
    << " cm, " << spec.speed_m_s << " m/s, " << spec.turn_deg_s << " deg/s, "
    << spec.depth_m * 1e3 << " mm deep, 1 ms apart, two 1 mm lift-offs";
  out.description = d.str();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  auto unit = [&] {
    Vector3 u;
    do u = Vector3(g(rng), g(rng), g(rng));
    while (u.norm() < 1e-9);
    return Vector3(u.normalized());
  };
  const Vector3 e1 = unit();
  const Vector3 e2 = e1.cross(unit()).normalized();
  const Vector3 axis = unit();
  const pd::Matrix3 R0 =
      pd::Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  const pd::Isometry3 X_WS = ScenePose(pair);
  const double r_max = pair.probe->model->radius() + pair.scene->model->radius();

  double theta = 0.0, theta_before = 0.0;
  double heading = 1.0;    // +1 or -1: which way along the great circle
  bool held = false;       // the last pose was wedged under an overhang
  double s_touch = r_max;  // radial distance of first contact (refined per step)
  double s = -1.0;         // the tool's radial distance
  const double T = steps * kHapticDt;
  for (int i = 0; i < steps; ++i) {
    const double t = i * kHapticDt;
    const pd::Matrix3 R = Eigen::AngleAxisd(spec.turn_deg_s * M_PI / 180.0 * t, axis) * R0;
    Vector3 u;
    auto collides = [&](double r) {
      const pd::ModelPair mp(*pair.probe->model, *pair.scene->model, ToolPose(pair, R, r * u),
                             X_WS);
      return pd::InCollision(mp, Vector3::Zero());
    };
    // Bracket first contact near the previous one, then bisect.
    const double step = 3e-3;
    double hi = 0.0, lo = 0.0;
    bool wedged = false;
    for (int attempt = 0; attempt < 2; ++attempt) {
      u = std::cos(theta) * e1 + std::sin(theta) * e2;
      hi = std::min(s_touch + step, r_max * 1.01), lo = s_touch - step;
      int raised = 0;
      while (collides(hi)) hi = std::min(hi + step, r_max * 1.01), ++raised;
      if (raised < 2 || s < 0) break;
      // The first contact along the ray rose more than 6 mm in one pose: an
      // overhang (an ear, a handle) has come over the tool. The surface the
      // hand follows is the one under the overhang, the top of the gap the
      // tool slides in; a hand does not climb through the overhang from below.
      hi = -1.0;
      for (double r = s_touch + kGapScan; r <= s_touch + 2 * step; r += kGapScan)
        if (!collides(r)) {
          hi = r, lo = r - kGapScan;
          break;
        }
      if (hi > 0) break;
      // No gap within 6 mm: the overhang has closed on the tool. The hand
      // turns back the way it came (once), holding its height meanwhile.
      if (attempt > 0 || held) {
        wedged = true;
        break;
      }
      heading = -heading, theta = theta_before;
    }
    held = wedged;
    if (!wedged) {
      while (lo > 0 && !collides(lo)) hi = lo, lo -= step;
      if (lo <= 0) lo = 0;  // no contact along this ray: keep the tool at the centre's side
      for (int b = 0; b < kBisections; ++b) {
        const double mid = 0.5 * (lo + hi);
        (collides(mid) ? lo : hi) = mid;
      }
      s_touch = hi;
    }
    const bool lifting = (t >= T / 3 && t < T / 3 + kLiftDuration) ||
                         (t >= 2 * T / 3 && t < 2 * T / 3 + kLiftDuration);
    const double target = s_touch + (lifting ? kLift : -spec.depth_m);
    // Start 2 mm clear and approach; then follow at the hand's speed.
    if (s < 0) s = s_touch + 2e-3;
    const double max_step = kMaxRadialSpeed * kHapticDt;
    s += std::clamp(target - s, -max_step, max_step);
    Case c;
    c.index = i;
    c.X_WP = ToolPose(pair, R, s * u);
    c.colliding = collides(s);
    out.cases.push_back(c);
    // A hand that digs in more than 1 mm deeper than it means to (the
    // surface rose faster than it followed) stops sliding until it has
    // climbed back, as a user pushed back by the wall would.
    theta_before = theta;
    if (s_touch - s <= spec.depth_m + 1e-3)
      theta += heading * spec.speed_m_s * kHapticDt / std::max(s, 1e-3);
  }
  return out;
}

}  // namespace pd_bench
