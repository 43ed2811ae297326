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

}  // namespace

bool SurfaceFartherThan(const CollisionModel& model, const Vector3& p_M, double radius,
                        ProximityCounters* counters) {
  const double r2 = radius * radius;
  const auto& mesh = model.mesh();
  const Bvh& bvh = model.bvh();
  int64_t boxes = 0, triangles = 0;
  const bool clear = DescendBvh(
      bvh, [&](const BvhNode& n) { return PointBoxDistance2(n, p_M) < r2; },
      [&](int first, int end) {
        for (int slot = first; slot < end; ++slot) {
          ++triangles;
          const auto& tri = mesh.triangles[bvh.order()[slot]];
          const Vector3 c = ClosestPointOnTriangle(p_M, mesh.vertices[tri[0]],
                                                   mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
          if ((c - p_M).squaredNorm() < r2) return false;
        }
        return true;
      },
      kBvhStackCapacity, &boxes);
  if (counters) {
    counters->box_tests += boxes;
    counters->triangle_tests += triangles;
  }
  return clear;
}

double SurfaceDistance(const CollisionModel& model, const Vector3& p_M, double max_distance,
                       ProximityCounters* counters) {
  double best2 = max_distance * max_distance;
  const auto& mesh = model.mesh();
  const Bvh& bvh = model.bvh();
  int64_t boxes = 0, triangles = 0;
  DescendBvh(
      bvh, [&](const BvhNode& n) { return PointBoxDistance2(n, p_M) < best2; },
      [&](int first, int end) {
        for (int slot = first; slot < end; ++slot) {
          ++triangles;
          const auto& tri = mesh.triangles[bvh.order()[slot]];
          const Vector3 c = ClosestPointOnTriangle(p_M, mesh.vertices[tri[0]],
                                                   mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
          best2 = std::min(best2, (c - p_M).squaredNorm());
        }
        return true;
      },
      kBvhStackCapacity, &boxes);
  if (counters) {
    counters->box_tests += boxes;
    counters->triangle_tests += triangles;
  }
  return std::sqrt(best2);
}

}  // namespace pd
