#include "pd_core/proximity/inner_sphere_overlap.h"

namespace pd {

bool InnerSpheresOverlap(const ModelPair& pair, const Vector3& offset_S) {
  if (pair.inner_spheres != nullptr && pair.inner_spheres->PlaceOnce(pair))
    return pair.inner_spheres->Overlap(pair, offset_S);
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

bool PlacedInnerSpheres::PlaceOnce(const ModelPair& pair) {
  if (placed_) return fits_;
  placed_ = true;
  const auto& spheres_P = pair.P.inner_spheres();
  const auto& spheres_S = pair.S.inner_spheres();
  fits_ = spheres_P.size() <= kCapacity && spheres_S.size() <= kCapacity;
  if (!fits_) return false;
  n_P_ = static_cast<int>(spheres_P.size());
  n_S_ = static_cast<int>(spheres_S.size());
  for (int i = 0; i < n_P_; ++i) {
    // X_SP * p less the translation (Overlap adds p_SP, then the offset,
    // the order of X_SP * p + offset_S).
    const Vector3 c = pair.X_SP.R_SP * spheres_P[i].p_MC;
    px_[i] = c.x(), py_[i] = c.y(), pz_[i] = c.z(), pr_[i] = spheres_P[i].radius;
  }
  for (int j = 0; j < n_S_; ++j) {
    const Vector3& c = spheres_S[j].p_MC;
    sx_[j] = c.x(), sy_[j] = c.y(), sz_[j] = c.z(), sr_[j] = spheres_S[j].radius;
  }
  return true;
}

bool PlacedInnerSpheres::Overlap(const ModelPair& pair, const Vector3& offset_S) const {
  if (n_P_ == 0 || n_S_ == 0) return false;
  const Vector3& p_SP = pair.X_SP.p_SP;
  for (int i = 0; i < n_P_; ++i) {
    if (pair.counters) ++pair.counters->box_tests;
    const double cx = (px_[i] + p_SP.x()) + offset_S.x();
    const double cy = (py_[i] + p_SP.y()) + offset_S.y();
    const double cz = (pz_[i] + p_SP.z()) + offset_S.z();
    const double ra = pr_[i];
    int hits = 0;
    for (int j = 0; j < n_S_; ++j) {
      const double dx = cx - sx_[j], dy = cy - sy_[j], dz = cz - sz_[j];
      const double reach = ra + sr_[j];
      hits += (dx * dx + dy * dy) + dz * dz < reach * reach;
    }
    if (hits > 0) return true;
  }
  return false;
}

}  // namespace pd
