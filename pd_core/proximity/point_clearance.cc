#include "pd_core/proximity/point_clearance.h"

#include <algorithm>
#include <cmath>

#include "pd_core/proximity/bvh_descent.h"
#include "pd_core/proximity/triangle_geometry.h"

namespace pd {
namespace {

// Squared distance from p_M to the node's box (0 inside), in the box's frame.
double PointBoxDistance2(const BvhNode& n, const Vector3& p_M) {
  const Vector3 p_B = n.R_MB.transpose() * (p_M - n.center_M);
  return (p_B.cwiseAbs() - n.half_B).cwiseMax(0.0).squaredNorm();
}

// The one descent of both queries: a triangle nearer than sqrt(*best2)
// shrinks it to that triangle's squared distance, and with stop_at_first
// ends the descent (returns false then).
bool DescendNearest(const CollisionModel& model, const Vector3& p_M, double* best2,
                    bool stop_at_first, ProximityCounters* counters) {
  const auto& mesh = model.mesh();
  const Bvh& bvh = model.bvh();
  int64_t boxes = 0, triangles = 0;
  const bool completed = DescendBvh(
      bvh, [&](const BvhNode& n) { return PointBoxDistance2(n, p_M) < *best2; },
      [&](int first, int end) {
        for (int slot = first; slot < end; ++slot) {
          ++triangles;
          const auto& tri = mesh.triangles[bvh.order()[slot]];
          const Vector3 c = ClosestPointOnTriangle(p_M, mesh.vertices[tri[0]],
                                                   mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
          const double d2 = (c - p_M).squaredNorm();
          if (d2 < *best2) {
            *best2 = d2;
            if (stop_at_first) return false;
          }
        }
        return true;
      },
      kBvhStackCapacity, &boxes);
  if (counters) {
    counters->box_tests += boxes;
    counters->triangle_tests += triangles;
  }
  return completed;
}

}  // namespace

bool SurfaceFartherThan(const CollisionModel& model, const Vector3& p_M, double radius,
                        ProximityCounters* counters) {
  double r2 = radius * radius;
  return DescendNearest(model, p_M, &r2, /*stop_at_first=*/true, counters);
}

double SurfaceDistance(const CollisionModel& model, const Vector3& p_M, double max_distance,
                       ProximityCounters* counters) {
  double best2 = max_distance * max_distance;
  DescendNearest(model, p_M, &best2, /*stop_at_first=*/false, counters);
  return std::sqrt(best2);
}

}  // namespace pd
