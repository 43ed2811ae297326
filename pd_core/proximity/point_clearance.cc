#include "pd_core/proximity/point_clearance.h"

#include "pd_core/proximity/bvh_descent.h"
#include "pd_core/proximity/triangle_geometry.h"

namespace pd {

bool SurfaceFartherThan(const CollisionModel& model, const Vector3& p_M, double radius,
                        ProximityCounters* counters) {
  const double r2 = radius * radius;
  const auto& mesh = model.mesh();
  const Bvh& bvh = model.bvh();
  int64_t boxes = 0, triangles = 0;
  const bool clear = DescendBvh(
      bvh,
      [&](const BvhNode& n) {
        // Distance from the point to the box, in the box's frame.
        const Vector3 p_B = n.R_MB.transpose() * (p_M - n.center_M);
        return (p_B.cwiseAbs() - n.half_B).cwiseMax(0.0).squaredNorm() < r2;
      },
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

}  // namespace pd
