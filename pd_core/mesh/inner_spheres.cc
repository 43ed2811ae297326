#include "pd_core/mesh/inner_spheres.h"

#include <algorithm>
#include <limits>

#include "pd_core/mesh/collision_model.h"
#include "pd_core/proximity/point_clearance.h"
#include "pd_core/proximity/point_in_mesh.h"

namespace pd {

std::vector<InnerSphere> ComputeInnerSpheres(const CollisionModel& model, int max_spheres,
                                             int grid) {
  std::vector<InnerSphere> out;
  const TriangleMesh& mesh = model.mesh();
  if (!model.closed() || mesh.num_triangles() == 0 || max_spheres <= 0 || grid <= 0) return out;
  const MeshBounds bounds = ComputeBounds(mesh);
  const Vector3 cell = (bounds.max - bounds.min) / grid;
  std::vector<InnerSphere> candidates;
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      // Along a row the clearance changes by at most the step (it is
      // 1-Lipschitz): the last point's bounds the next one's descent.
      double reach = inf;
      for (int k = 0; k < grid; ++k, reach += cell.z()) {
        const Vector3 p = bounds.min + cell.cwiseProduct(Vector3(i + 0.5, j + 0.5, k + 0.5));
        if (!PointInsideMesh(model, p)) {
          reach = inf;
          continue;
        }
        const double r = SurfaceDistance(model, p, reach);
        reach = r;
        if (r > 0.0) candidates.push_back({p, r * (1.0 - 1e-6)});
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const InnerSphere& a, const InnerSphere& b) { return a.radius > b.radius; });
  for (const InnerSphere& c : candidates) {
    if (static_cast<int>(out.size()) >= max_spheres) break;
    const bool apart = std::all_of(out.begin(), out.end(), [&](const InnerSphere& o) {
      return (c.p_MC - o.p_MC).norm() >= std::max(c.radius, o.radius);
    });
    if (apart) out.push_back(c);
  }
  return out;
}

}  // namespace pd
