#include "pd_core/translational_ccd.h"

#include "pd_core/box_overlap.h"
#include "pd_core/bvh_pair_traversal.h"
#include "pd_core/triangle_geometry.h"

namespace pd {

double FirstContactAlongTranslation(const ModelPair& pair, const Vector3& offset_S,
                                    const Vector3& sweep_S) {
  double s_best = 1.0;
  bool hit = false;
  const auto& own_P = pair.P.owned_features();
  const auto& own_S = pair.S.owned_features();
  const Vector3 back_S = -sweep_S;
  TraverseBvhPairs(
      pair.P.bvh(), pair.S.bvh(),
      [&](const BvhNode& a, const BvhNode& b) {
        return BoxGapLowerBound(ProbeBox(a, pair.X_SP, offset_S), b, pair.X_SP,
                                s_best * sweep_S) <= 0;
      },
      [&](int tp, int ts) {
        Vector3 p[3], s[3];
        pair.ProbeTriangle(tp, offset_S, p);
        pair.SceneTriangle(ts, s);
        const uint8_t op = own_P[tp], os = own_S[ts];
        auto consider = [&](double t) {
          if (t >= 0 && t <= s_best) {
            s_best = t;
            hit = true;
          }
        };
        for (int k = 0; k < 3; ++k) {
          // Probe vertex k (if owned) against the scene face.
          if (op & (1u << k)) consider(RayTriangle(p[k], sweep_S, s[0], s[1], s[2], s_best));
          // Scene vertex k against the probe face, moving the other way.
          if (os & (1u << k)) consider(RayTriangle(s[k], back_S, p[0], p[1], p[2], s_best));
        }
        for (int i = 0; i < 3; ++i) {
          if (!(op & (8u << i))) continue;
          for (int j = 0; j < 3; ++j) {
            if (!(os & (8u << j))) continue;
            consider(EdgeEdgeTranslationalContact(p[i], p[(i + 1) % 3], s[j], s[(j + 1) % 3],
                                                  sweep_S, s_best));
          }
        }
        return true;
      });
  return hit ? s_best : -1.0;
}

}  // namespace pd
