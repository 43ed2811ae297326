#pragma once
// The Minkowski difference D = S - P of the cores of two convex geometries
// placed in world (scene S at X_WS, probe P at X_WP), as a support function.
// The probe moved by t_W overlaps S iff t_W is in D ⊕ ball(margin), margin =
// the sum of the geometries' margins (sphere and capsule radii), so the PD is
// the distance from the origin to the boundary of that set.
#include "pd_core/geometry/geometry.h"
#include "pd_core/geometry/pose.h"

namespace pd {

struct MinkowskiDifference {
  const Geometry* probe;
  const Geometry* scene;
  Isometry3 X_WP, X_WS;

  double margin() const { return probe->margin() + scene->margin(); }
  // Support point of the cores' difference along d_W (need not be unit).
  Vector3 Support(const Vector3& d_W) const {
    const Vector3 s_W = X_WS * scene->CoreSupport(X_WS.linear().transpose() * d_W);
    const Vector3 p_W = X_WP * probe->CoreSupport(X_WP.linear().transpose() * (-d_W));
    return s_W - p_W;
  }
  // Support value of the full shapes' difference along a unit n_W:
  // h_S(n) + h_P(-n). The probe moved by t_W is free when n_W·t_W >= it.
  double FullSupportValue(const Vector3& n_W) const {
    const Vector3 s_W = X_WS * scene->Support(X_WS.linear().transpose() * n_W);
    const Vector3 p_W = X_WP * probe->Support(X_WP.linear().transpose() * (-n_W));
    return n_W.dot(s_W - p_W);
  }
};

}  // namespace pd
