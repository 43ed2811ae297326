// Contact localisation (contact_constraints.h) against a brute-force
// reference: every feature pair of the two meshes clearly within the contact
// distance, found without the BVH, the candidate lists or any pruning, must
// be among the localised constraints.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/proximity/model_pair.h"
#include "tests/pd_core/point_triangle_distance.h"

namespace pd {
namespace {

// Closest points of segments a0a1 and b0b1 by sampling-free closed form for
// non-parallel segments whose closest points are interior (all this test
// asks for): the parameters of the infinite lines' common perpendicular.
bool InteriorLineClosest(const Vector3& a0, const Vector3& a1, const Vector3& b0,
                         const Vector3& b1, double* u, double* v, double* dist) {
  const Vector3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.dot(d1), e = d2.dot(d2), b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
  const double den = a * e - b * b;
  if (den <= 1e-12 * a * e) return false;
  *u = (b * f - c * e) / den;
  *v = (a * f - b * c) / den;
  *dist = ((a0 + *u * d1) - (b0 + *v * d2)).norm();
  return true;
}

using Key = std::tuple<int, int, int>;  // kind, feature_P, feature_S

// Probe poses near and across the scene's surface, so some triangle pairs
// are within the contact distance, some intersect and most are farther.
TEST(ContactConstraints, HoldEveryFeaturePairClearlyWithinTheDistance) {
  auto P = CollisionModel::Build(MakeIcosphere(0.3, 3));
  auto S = CollisionModel::Build(MakeTorusKnot(2, 3, 0.2, 1.0, 64, 8));
  const auto& VP = P->mesh().vertices;
  const auto& TP = P->mesh().triangles;
  const auto& TS = S->mesh().triangles;
  const auto& VS = S->mesh().vertices;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int checked_vf = 0, checked_fv = 0, checked_ee = 0;
  for (int trial = 0; trial < 6; ++trial) {
    Isometry3 X_WP = Isometry3::Identity();
    X_WP.linear() = Quaternion(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
    X_WP.translation() = VS[rng() % VS.size()] + 0.3 * Vector3(U(rng), U(rng), U(rng));
    const Isometry3 X_WS = Isometry3::Identity();
    ModelPair pair(*P, *S, X_WP, X_WS);
    const double distance = 0.03;
    const Vector3 q_S = Vector3::Zero();
    std::vector<ContactConstraint> cs;
    CollectContactConstraints(pair, q_S, distance, &cs);
    std::set<Key> found;
    for (const ContactConstraint& c : cs)
      found.insert({static_cast<int>(c.kind), c.feature_P, c.feature_S});

    std::vector<Vector3> p_S(VP.size());
    for (size_t i = 0; i < VP.size(); ++i) p_S[i] = pair.X_SP * VP[i];
    const double clear = 0.97 * distance, outside = 1e-3 * distance;
    // Vertex of P against face of S, and face of P against vertex of S:
    // within the distance and clearly on the outer side of the face.
    for (size_t ts = 0; ts < TS.size(); ++ts) {
      const Vector3 &a = VS[TS[ts][0]], &b = VS[TS[ts][1]], &c = VS[TS[ts][2]];
      const Vector3 n = (b - a).cross(c - a).normalized();
      for (size_t v = 0; v < p_S.size(); ++v) {
        if (n.dot(p_S[v] - a) <= outside || test::PointTriangleDistance(p_S[v], a, b, c) >= clear)
          continue;
        ++checked_vf;
        EXPECT_TRUE(found.count({static_cast<int>(FeaturePairKind::kVertexFace), int(v), int(ts)}))
            << "trial " << trial << " probe vertex " << v << " scene face " << ts;
      }
    }
    for (size_t tp = 0; tp < TP.size(); ++tp) {
      const Vector3 &a = p_S[TP[tp][0]], &b = p_S[TP[tp][1]], &c = p_S[TP[tp][2]];
      const Vector3 n = (b - a).cross(c - a).normalized();
      for (size_t v = 0; v < VS.size(); ++v) {
        if (n.dot(VS[v] - a) <= outside || test::PointTriangleDistance(VS[v], a, b, c) >= clear)
          continue;
        ++checked_fv;
        EXPECT_TRUE(found.count({static_cast<int>(FeaturePairKind::kFaceVertex), int(tp), int(v)}))
            << "trial " << trial << " probe face " << tp << " scene vertex " << v;
      }
    }
    // Edge of P against edge of S: closest points inside both edges, not
    // near-parallel, and clearly apart (so the gap decides the side).
    const auto& EP = P->topology().edges;
    const auto& ES = S->topology().edges;
    for (size_t ep = 0; ep < EP.size(); ++ep) {
      const Vector3 &a0 = p_S[EP[ep].v0], &a1 = p_S[EP[ep].v1];
      for (size_t es = 0; es < ES.size(); ++es) {
        const Vector3 &b0 = VS[ES[es].v0], &b1 = VS[ES[es].v1];
        if ((0.5 * (a0 + a1) - 0.5 * (b0 + b1)).norm() >
            0.5 * ((a1 - a0).norm() + (b1 - b0).norm()) + distance)
          continue;
        double u, v, dist;
        if (!InteriorLineClosest(a0, a1, b0, b1, &u, &v, &dist)) continue;
        if (u < 0.02 || u > 0.98 || v < 0.02 || v > 0.98) continue;
        if (dist >= clear || dist <= outside) continue;
        if ((a1 - a0).cross(b1 - b0).norm() <= 1e-3 * (a1 - a0).norm() * (b1 - b0).norm())
          continue;
        ++checked_ee;
        EXPECT_TRUE(found.count({static_cast<int>(FeaturePairKind::kEdgeEdge), int(ep), int(es)}))
            << "trial " << trial << " probe edge " << ep << " scene edge " << es;
      }
    }
  }
  // The poses put real work in front of every part of the check.
  EXPECT_GT(checked_vf, 20);
  EXPECT_GT(checked_fv, 20);
  EXPECT_GT(checked_ee, 20);
}

}  // namespace
}  // namespace pd
