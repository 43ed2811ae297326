#include "pd_core/polydepth/contact_regions.h"

#include <cmath>

namespace pd {

void GroupContactRegions(const std::vector<ContactConstraint>& constraints, const Vector3& q_S,
                         const Isometry3& X_WS, double merge_distance,
                         PenetrationResult* result) {
  // Normals within ~8 degrees describe one face of the contact space.
  constexpr double kSameNormalCos = 0.99;
  const double depth_floor = 1e-9 * (q_S.norm() + merge_distance);
  std::array<Vector3, kMaxContactRegions> sum_p;
  std::array<Vector3, kMaxContactRegions> first_p;
  std::array<Vector3, kMaxContactRegions> n_S;
  int count = 0;
  for (const ContactConstraint& c : constraints) {
    const double local = q_S.dot(c.n_S);
    if (local <= depth_floor) continue;  // not pushing against this pair
    int best = -1;
    double best_d2 = 1e300;
    for (int r = 0; r < count; ++r) {
      if (n_S[r].dot(c.n_S) < kSameNormalCos) continue;
      const double d2 = (first_p[r] - c.p_S).squaredNorm();
      if (d2 <= merge_distance * merge_distance && d2 < best_d2) best = r, best_d2 = d2;
    }
    if (best < 0 && count == kMaxContactRegions) {
      // Out of slots: join the region with the closest normal.
      double best_dot = -2.0;
      for (int r = 0; r < count; ++r)
        if (n_S[r].dot(c.n_S) > best_dot) best_dot = n_S[r].dot(c.n_S), best = r;
    }
    if (best < 0) {
      best = count++;
      sum_p[best] = Vector3::Zero();
      first_p[best] = c.p_S;
      n_S[best] = c.n_S;
      result->regions[best].num_features = 0;
    }
    sum_p[best] += c.p_S;
    result->regions[best].num_features += 1;
  }
  const Matrix3 R_WS = X_WS.linear();
  for (int r = 0; r < count; ++r) {
    ContactRegion& region = result->regions[r];
    // Feature points were found with the probe moved by q_S; undo it to get
    // the point on the probe at the query pose.
    const Vector3 p_S = sum_p[r] / region.num_features - q_S;
    region.p_W = X_WS * p_S;
    region.n_W = R_WS * n_S[r];
    region.local_depth = q_S.dot(n_S[r]);
  }
  result->num_regions = count;
}

}  // namespace pd
