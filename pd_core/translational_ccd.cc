#include "pd_core/translational_ccd.h"

#include <array>

#include "pd_core/box_overlap.h"
#include "pd_core/candidate_pairs.h"
#include "pd_core/triangle_geometry.h"

namespace pd {
namespace {

// Earliest contact of one probe triangle swept along sweep_S with one scene
// triangle, over the features each owns. Lowers *s_best on a hit.
void TriangleFirstContact(const ModelPair& pair, int tp, int ts, const Vector3& offset_S,
                          const Vector3& sweep_S, double* s_best, bool* hit) {
  Vector3 p[3], s[3];
  pair.ProbeTriangle(tp, offset_S, p);
  pair.SceneTriangle(ts, s);
  const uint8_t op = pair.P.owned_features()[tp], os = pair.S.owned_features()[ts];
  auto consider = [&](double t) {
    if (t >= 0 && t <= *s_best) {
      *s_best = t;
      *hit = true;
    }
  };
  const Vector3 back_S = -sweep_S;
  for (int k = 0; k < 3; ++k) {
    if (op & (1u << k)) consider(RayTriangle(p[k], sweep_S, s[0], s[1], s[2], *s_best));
    if (os & (1u << k)) consider(RayTriangle(s[k], back_S, p[0], p[1], p[2], *s_best));
  }
  for (int i = 0; i < 3; ++i) {
    if (!(op & (8u << i))) continue;
    for (int j = 0; j < 3; ++j) {
      if (!(os & (8u << j))) continue;
      consider(EdgeEdgeTranslationalContact(p[i], p[(i + 1) % 3], s[j], s[(j + 1) % 3], sweep_S,
                                            *s_best));
    }
  }
}

}  // namespace

double FirstContactAlongTranslation(const ModelPair& pair, const Vector3& offset_S,
                                    const Vector3& sweep_S) {
  const Bvh& bvh_P = pair.P.bvh();
  const Bvh& bvh_S = pair.S.bvh();
  if (bvh_P.empty() || bvh_S.empty()) return -1.0;
  const auto& nodes_P = bvh_P.nodes();
  const auto& nodes_S = bvh_S.nodes();
  double s_best = 1.0;
  bool hit = false;
  double lo, hi;
  const double covered =
      pair.candidates ? pair.candidates->CoveredFraction(pair, offset_S, sweep_S, 0.0) : -1.0;
  if (covered > 0.0) {
    // Every pair that can touch on [0, covered] is listed; a first contact
    // found there is exact. Past it, fall back to the full descent.
    s_best = covered;
    for (const auto& [ip, is] : pair.candidates->leaf_pairs()) {
      const BvhNode& a = nodes_P[ip];
      const BvhNode& b = nodes_S[is];
      if (!SweptBoxContactInterval(ProbeBox(a, pair.X_SP, offset_S), b, sweep_S, s_best, &lo,
                                   &hi))
        continue;
      for (int i = 0; i < a.count; ++i)
        for (int j = 0; j < b.count; ++j)
          TriangleFirstContact(pair, bvh_P.order()[a.right_or_first + i],
                               bvh_S.order()[b.right_or_first + j], offset_S, sweep_S, &s_best,
                               &hit);
    }
    if (hit) return s_best;
    if (covered >= 1.0) return -1.0;
    s_best = 1.0;
  }

  // Depth-first, nearer-in-time child pair first, pruning every node pair
  // whose earliest possible contact is later than the best contact so far.
  struct Entry {
    int ip, is;
    double s_lo;
  };
  std::array<Entry, 256> stack;
  int top = 0;
  if (!SweptBoxContactInterval(ProbeBox(nodes_P[0], pair.X_SP, offset_S), nodes_S[0],
                               sweep_S, s_best, &lo, &hi))
    return -1.0;
  stack[top++] = {0, 0, lo};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.s_lo > s_best) continue;
    const BvhNode& a = nodes_P[e.ip];
    const BvhNode& b = nodes_S[e.is];
    if (a.is_leaf() && b.is_leaf()) {
      for (int i = 0; i < a.count; ++i)
        for (int j = 0; j < b.count; ++j)
          TriangleFirstContact(pair, bvh_P.order()[a.right_or_first + i],
                               bvh_S.order()[b.right_or_first + j], offset_S, sweep_S, &s_best,
                               &hit);
      continue;
    }
    const bool split_P =
        b.is_leaf() || (!a.is_leaf() && NodeSize2(a) >= NodeSize2(b));
    Entry child[2];
    int n = 0;
    for (int c = 0; c < 2; ++c) {
      const int ip = split_P ? (c == 0 ? e.ip + 1 : a.right_or_first) : e.ip;
      const int is = split_P ? e.is : (c == 0 ? e.is + 1 : b.right_or_first);
      if (SweptBoxContactInterval(ProbeBox(nodes_P[ip], pair.X_SP, offset_S), nodes_S[is],
                                  sweep_S, s_best, &lo, &hi))
        child[n++] = {ip, is, lo};
    }
    if (n == 2 && child[0].s_lo < child[1].s_lo) std::swap(child[0], child[1]);
    for (int c = 0; c < n; ++c) stack[top++] = child[c];
  }
  return hit ? s_best : -1.0;
}

}  // namespace pd
