#include "bench/cases/scenarios.h"

#include <cmath>
#include <random>

#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

namespace pd_bench {
namespace {

using pd::Isometry3;
using pd::Vector3;

// Probe pose with rotation R and bounding-box centre at c_W.
Isometry3 ProbePose(const BenchPair& pair, const pd::Matrix3& R, const Vector3& c_W) {
  Isometry3 X = Isometry3::Identity();
  X.linear() = R;
  X.translation() = c_W - R * pair.probe->model->center();
  return X;
}

bool Collides(const BenchPair& pair, const Isometry3& X_WP) {
  const pd::ModelPair mp(*pair.probe->model, *pair.scene->model, X_WP, ScenePose(pair));
  return pd::InCollision(mp, Vector3::Zero());
}

Vector3 RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vector3 u;
  do u = Vector3(g(rng), g(rng), g(rng));
  while (u.norm() < 1e-9);
  return u.normalized();
}

pd::Matrix3 RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return pd::Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

pd::Matrix3 AxisAngle(const Vector3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

}  // namespace

const char* ScenarioName(Scenario s) {
  switch (s) {
    case Scenario::kRandom: return "random";
    case Scenario::kPath: return "path";
    case Scenario::kShallow: return "shallow";
  }
  return "?";
}

Isometry3 ScenePose(const BenchPair& pair) {
  Isometry3 X = Isometry3::Identity();
  X.translation() = -pair.scene->model->center();
  return X;
}

ScenarioCases RandomCases(const BenchPair& pair, int count, uint64_t seed) {
  ScenarioCases out{Scenario::kRandom,
                    "random orientation, probe centre at a random direction and distance "
                    "U[0.1, 0.8] x scene radius from the scene centre; colliding only; "
                    "cold solves (coherent=false, a fresh solver per case)",
                    {}};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> frac(0.1, 0.8);
  const double r_scene = pair.scene->model->radius();
  // Bounded tries: a pair that rarely collides yields fewer cases, not a hang.
  for (int tries = 0; tries < 50 * count && static_cast<int>(out.cases.size()) < count; ++tries) {
    const pd::Matrix3 R = RandomRotation(rng);
    const Vector3 c = frac(rng) * r_scene * RandomUnit(rng);
    Case k;
    k.X_WP = ProbePose(pair, R, c);
    k.colliding = Collides(pair, k.X_WP);
    if (!k.colliding) continue;
    k.index = static_cast<int>(out.cases.size());
    out.cases.push_back(k);
  }
  return out;
}

ScenarioCases PathCases(const BenchPair& pair, int steps, uint64_t seed) {
  ScenarioCases out{Scenario::kPath,
                    "straight line through the scene (0.2 scene radii from its centre, "
                    "-1.2..+1.2 radii) with a 90 deg rotation over the path; coherent solves",
                    {}};
  std::mt19937_64 rng(seed);
  const double r = pair.scene->model->radius();
  const Vector3 dir = RandomUnit(rng);
  Vector3 side = dir.cross(RandomUnit(rng));
  side.normalize();
  const Vector3 axis = RandomUnit(rng);
  const pd::Matrix3 R0 = RandomRotation(rng);
  for (int i = 0; i < steps; ++i) {
    const double t = steps > 1 ? static_cast<double>(i) / (steps - 1) : 0.5;
    const Vector3 c = 0.2 * r * side + (-1.2 + 2.4 * t) * r * dir;
    Case k;
    k.index = i;
    k.X_WP = ProbePose(pair, AxisAngle(axis, 0.5 * M_PI * t) * R0, c);
    k.colliding = Collides(pair, k.X_WP);
    out.cases.push_back(k);
  }
  return out;
}

ScenarioCases ShallowCases(const BenchPair& pair, int steps, double depth_fraction,
                           uint64_t seed) {
  ScenarioCases out{Scenario::kShallow,
                    "probe sliding around the scene on half a great circle, 45 deg rotation "
                    "over the path, pushed in radially by " +
                        std::to_string(depth_fraction * 100).substr(0, 4) +
                        "% of (probe + scene radius) from first contact; coherent solves",
                    {}};
  std::mt19937_64 rng(seed);
  const double size = pair.probe->model->radius() + pair.scene->model->radius();
  const double push = depth_fraction * size;
  const Vector3 e1 = RandomUnit(rng);
  const Vector3 e2 = e1.cross(RandomUnit(rng)).normalized();
  const Vector3 axis = RandomUnit(rng);
  const pd::Matrix3 R0 = RandomRotation(rng);
  const double march = 0.005 * size;  // inward step when looking for first contact
  double s_prev = size * 1.05;        // bounding spheres disjoint there: free
  for (int i = 0; i < steps; ++i) {
    const double t = steps > 1 ? static_cast<double>(i) / (steps - 1) : 0.0;
    const Vector3 u = std::cos(M_PI * t) * e1 + std::sin(M_PI * t) * e2;
    const pd::Matrix3 R = AxisAngle(axis, 0.25 * M_PI * t) * R0;
    auto free_at = [&](double s) { return !Collides(pair, ProbePose(pair, R, s * u)); };
    // A free start a little outside the previous contact distance.
    double s_free = std::min(s_prev + 0.05 * size, size * 1.05);
    while (!free_at(s_free)) s_free = std::min(s_free + 0.05 * size, size * 1.05);
    // March in to the first contact, then bisect the free/colliding bracket.
    double s_hit = s_free - march;
    while (s_hit > 0 && free_at(s_hit)) s_free = s_hit, s_hit -= march;
    if (s_hit <= 0) continue;  // no contact along this ray (e.g. through a hole)
    for (int b = 0; b < 30; ++b) {
      const double mid = 0.5 * (s_free + s_hit);
      (free_at(mid) ? s_free : s_hit) = mid;
    }
    s_prev = s_free;
    Case k;
    k.index = i;
    k.X_WP = ProbePose(pair, R, (s_free - push) * u);
    k.colliding = Collides(pair, k.X_WP);
    out.cases.push_back(k);
  }
  return out;
}

}  // namespace pd_bench
