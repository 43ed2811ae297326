#pragma once
// Point-triangle distance for tests, written here (not taken from pd_core)
// so that tests of pd_core's distance and localisation queries have an
// independent reference.
#include <algorithm>
#include <cmath>

#include "pd_core/geometry/pose.h"
#include "pd_core/mesh/mesh.h"

namespace pd {
namespace test {

// Distance from p to triangle abc, by the plane when the projection falls
// inside, else by the three edges (written here, not taken from pd_core).
inline double PointTriangleDistance(const Vector3& p, const Vector3& a, const Vector3& b,
                             const Vector3& c) {
  auto segment = [](const Vector3& x, const Vector3& s0, const Vector3& s1) {
    const Vector3 d = s1 - s0;
    const double t = std::clamp((x - s0).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (x - (s0 + t * d)).norm();
  };
  const Vector3 n = (b - a).cross(c - a).normalized();
  const Vector3 f = p - n.dot(p - a) * n;
  const bool inside = (b - a).cross(f - a).dot(n) >= 0 && (c - b).cross(f - b).dot(n) >= 0 &&
                      (a - c).cross(f - c).dot(n) >= 0;
  if (inside) return std::abs(n.dot(p - a));
  return std::min({segment(p, a, b), segment(p, b, c), segment(p, c, a)});
}

// Distance from p to a mesh's surface over every triangle (no BVH).
inline double BruteForceSurfaceDistance(const TriangleMesh& mesh, const Vector3& p) {
  double best = 1e300;
  for (const auto& t : mesh.triangles)
    best = std::min(best, PointTriangleDistance(p, mesh.vertices[t[0]], mesh.vertices[t[1]],
                                                mesh.vertices[t[2]]));
  return best;
}

}  // namespace test
}  // namespace pd
