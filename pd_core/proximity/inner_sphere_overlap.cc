#include "pd_core/proximity/inner_sphere_overlap.h"

namespace pd {

bool InnerSpheresOverlap(const ModelPair& pair, const Vector3& offset_S) {
  const auto& spheres_P = pair.P.inner_spheres();
  const auto& spheres_S = pair.S.inner_spheres();
  if (spheres_P.empty() || spheres_S.empty()) return false;
  for (const InnerSphere& a : spheres_P) {
    if (pair.counters) ++pair.counters->box_tests;
    const Vector3 p_SA = pair.X_SP * a.p_MC + offset_S;
    for (const InnerSphere& b : spheres_S) {
      const double reach = a.radius + b.radius;
      if ((p_SA - b.p_MC).squaredNorm() < reach * reach) return true;
    }
  }
  return false;
}

}  // namespace pd
