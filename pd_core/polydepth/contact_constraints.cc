#include "pd_core/polydepth/contact_constraints.h"

#include <algorithm>
#include <cmath>

#include "pd_core/proximity/box_overlap.h"
#include "pd_core/proximity/leaf_pairs_near.h"
#include "pd_core/proximity/placed_probe_triangles.h"
#include "pd_core/proximity/triangle_geometry.h"

namespace pd {
namespace {

// True if unit n lies in the cone spanned by the outward normals of the faces
// at an edge (its Gauss-map arc), with a small angular slack. For a boundary
// edge (one face) the half-circle on that face's side counts.
bool InEdgeNormalCone(const Vector3& n, const Vector3& edge, const Vector3& n0,
                      const Vector3* n1) {
  constexpr double kSlack = 1e-6;
  if (n1 == nullptr) return n.dot(n0) >= -kSlack;
  const double a = n0.cross(n).dot(edge);
  const double b = n.cross(*n1).dot(edge);
  const double e = kSlack * edge.norm();
  return ((a >= -e && b >= -e) || (a <= e && b <= e)) && n.dot(n0 + *n1) >= -kSlack;
}

}  // namespace

namespace {

// Shared by both entry points; with test_intersection, stops (returning
// false) at the first intersecting triangle pair.
bool Localise(const ModelPair& pair, const Vector3& q_S, double distance, bool test_intersection,
              std::vector<ContactConstraint>* out, CollisionWitness* witness,
              LeafPairRecord* record) {
  WorkScope scope(pair.counters, QueryKind::kLocalisation);
  out->clear();
  // Recording: the leaf pairs found (every one within `reach` at q_S, by
  // whichever path ForEachLeafPairNear takes) become the record at q_S.
  const bool recording = record != nullptr && !record->Covers(q_S, q_S, distance);
  const double reach = recording ? std::max(distance, record->distance) : distance;
  if (recording) {
    record->Invalidate();
    record->pairs.clear();
  }
  bool free = true;
  const double dist2 = distance * distance;
  // Plane distances beyond this prove a pair farther than `distance` (the
  // slack keeps round-off from dropping a pair the exact tests would keep).
  const double far = distance * (1.0 + 1e-9) + 1e-12 * pair.size();
  // A feature pair on the wrong side by more than this is not a touching pair.
  const double below = 1e-9 * pair.size();
  const auto& own_P = pair.P.owned_features();
  const auto& own_S = pair.S.owned_features();
  const auto& normals_P = pair.P.face_normals();
  const auto& normals_S = pair.S.face_normals();
  const auto& topo_P = pair.P.topology();
  const auto& topo_S = pair.S.topology();
  const bool closed_P = pair.P.closed(), closed_S = pair.S.closed();

  // The triangle pair whose features are being collected (see add).
  int tri_P = -1, tri_S = -1;
  auto add = [&](const Vector3& n, double h, const Vector3& p, FeaturePairKind kind, int f_P,
                 int f_S) {
    ContactConstraint c;
    c.tri_P = tri_P;
    c.tri_S = tri_S;
    c.n_S = n;
    c.c = n.dot(q_S) - h;  // so n·q - c = h at this configuration
    c.p_S = p;
    c.kind = kind;
    c.feature_P = f_P;
    c.feature_S = f_S;
    out->push_back(c);
  };
  // Chooses the separating side of a face normal: outward for closed meshes,
  // the side the other feature is on for open ones.
  auto oriented = [&](const Vector3& n_out, double h, bool closed) {
    return (closed || h >= 0) ? n_out : Vector3(-n_out);
  };

  const auto& tris_P = pair.P.mesh().triangles;
  const auto& tris_S = pair.S.mesh().triangles;
  ProbeBoxMemo probe_box(pair.X_SP, q_S, pair.probe_boxes, pair.P.bvh().nodes().data());
  PlacedProbeTriangles placed(pair, q_S);
  ForEachLeafPairNear(
      pair, q_S, q_S, reach,
      // Face axes alone, leaf pairs too: a pair the nine edge-edge axes
      // would have rejected costs a few triangle tests, which reject it on
      // their own (its features are farther than `distance`); skipping those
      // axes on every pair saves more (a median warm query: 10-15%).
      [&](const BvhNode& a, const BvhNode& b) {
        return BoxesWithin<BoxAxes::kFaces>(probe_box(a), b, reach);
      },
      [&](int ip, int is) {
       if (recording) record->pairs.push_back({ip, is});
       return ForEachTrianglePair(pair.P.bvh(), pair.S.bvh(), ip, is, [&](int tp, int ts) {
        if (pair.counters) ++pair.counters->triangle_tests;
        tri_P = tp;
        tri_S = ts;
        const PlacedProbeTriangles::Triangle& probe = placed(tp);
        const Vector3* p = probe.p;
        Vector3 s[3];
        pair.SceneTriangle(ts, s);
        const Vector3& nS = normals_S[ts];
        const Vector3& nP = probe.n;
        // A triangle wholly on one side of the other's plane, farther than
        // `distance`, is farther than that from every feature of it: no
        // constraint and no intersection (most pairs of a leaf-pair list).
        if (TriangleStaysOffPlane(nS, s[0], p, 0.0, far) ||
            TriangleStaysOffPlane(nP, p[0], s, 0.0, far))
          return true;
        if (test_intersection && TrianglesIntersect(p[0], p[1], p[2], s[0], s[1], s[2])) {
          free = false;
          if (witness) *witness = {tp, ts};
          return false;
        }
        const uint8_t op = own_P[tp], os = own_S[ts];
        for (int k = 0; k < 3; ++k) {
          if ((op & (1u << k)) && !nS.isZero()) {
            const Vector3 cp = ClosestPointOnTriangle(p[k], s[0], s[1], s[2]);
            if ((p[k] - cp).squaredNorm() <= dist2) {
              const double h0 = nS.dot(p[k] - s[0]);
              const Vector3 n = oriented(nS, h0, closed_S);
              const double h = n.dot(p[k] - s[0]);
              if (h >= -below) add(n, h, p[k], FeaturePairKind::kVertexFace, tris_P[tp][k], ts);
            }
          }
          if ((os & (1u << k)) && !nP.isZero()) {
            const Vector3 cp = ClosestPointOnTriangle(s[k], p[0], p[1], p[2]);
            if ((s[k] - cp).squaredNorm() <= dist2) {
              const double h0 = nP.dot(s[k] - p[0]);
              const Vector3 m = oriented(nP, h0, closed_P);
              const double h = m.dot(s[k] - p[0]);
              if (h >= -below) add(-m, h, cp, FeaturePairKind::kFaceVertex, tp, tris_S[ts][k]);
            }
          }
        }
        for (int i = 0; i < 3; ++i) {
          if (!(op & (8u << i))) continue;
          const Vector3 &a0 = p[i], &a1 = p[(i + 1) % 3];
          const Vector3 ea = a1 - a0;
          const MeshEdge& edge_P = topo_P.edges[topo_P.triangle_edges[tp][i]];
          for (int j = 0; j < 3; ++j) {
            if (!(os & (8u << j))) continue;
            const Vector3 &b0 = s[j], &b1 = s[(j + 1) % 3];
            double u, v;
            Vector3 pa, pb;
            if (ClosestSegmentSegment(a0, a1, b0, b1, &u, &v, &pa, &pb) > dist2) continue;
            // Endpoint contacts are vertex contacts: the vertex-face pairs of
            // the neighbouring faces describe them.
            if (u <= 0 || u >= 1 || v <= 0 || v >= 1) continue;
            const Vector3 eb = b1 - b0;
            Vector3 n = ea.cross(eb);
            const double len = n.norm();
            // Near-parallel edges: their contact is a face contact, already
            // given by vertex-face pairs; a cross product here is noise.
            if (len <= 1e-6 * ea.norm() * eb.norm()) continue;
            n /= len;
            const MeshEdge& edge_S = topo_S.edges[topo_S.triangle_edges[ts][j]];
            const Vector3 nS1 = edge_S.f1 >= 0 ? normals_S[edge_S.f1] : Vector3::Zero();
            const Vector3 nS0 = normals_S[edge_S.f0];
            const Vector3 nP0 = pair.X_SP.R_SP * normals_P[edge_P.f0];
            const Vector3 nP1 =
                edge_P.f1 >= 0 ? Vector3(pair.X_SP.R_SP * normals_P[edge_P.f1]) : Vector3::Zero();
            const double gap = n.dot(pa - pb);
            if (std::abs(gap) > 1e-3 * distance) {
              if (gap < 0) n = -n;  // clearly apart: the gap gives the side
            } else {
              // Touching: the side is where both edges' normal cones agree.
              const bool plus =
                  InEdgeNormalCone(n, eb, nS0, edge_S.f1 >= 0 ? &nS1 : nullptr) &&
                  InEdgeNormalCone(-n, ea, nP0, edge_P.f1 >= 0 ? &nP1 : nullptr);
              const bool minus =
                  InEdgeNormalCone(-n, eb, nS0, edge_S.f1 >= 0 ? &nS1 : nullptr) &&
                  InEdgeNormalCone(n, ea, nP0, edge_P.f1 >= 0 ? &nP1 : nullptr);
              if (plus == minus) continue;  // not a face of the Minkowski difference
              if (minus) n = -n;
            }
            add(n, n.dot(pa - pb), pa, FeaturePairKind::kEdgeEdge, topo_P.triangle_edges[tp][i],
                topo_S.triangle_edges[ts][j]);
          }
        }
        return true;
       });
      });
  if (recording && free) {
    record->q_S = q_S;
    record->valid = true;
  }
  return free;
}

}  // namespace

void CollectContactConstraints(const ModelPair& pair, const Vector3& q_S, double distance,
                               std::vector<ContactConstraint>* out, LeafPairRecord* record) {
  Localise(pair, q_S, distance, false, out, nullptr, record);
}

bool CollectContactConstraintsIfSurfacesFree(const ModelPair& pair, const Vector3& q_S,
                                             double distance,
                                             std::vector<ContactConstraint>* out,
                                             CollisionWitness* witness, LeafPairRecord* record) {
  return Localise(pair, q_S, distance, true, out, witness, record);
}

void RefreshContactConstraints(const ModelPair& pair, const Vector3& q_S,
                               const std::vector<ContactConstraint>& in,
                               std::vector<ContactConstraint>* out) {
  out->clear();
  const auto& V_P = pair.P.mesh().vertices;
  const auto& V_S = pair.S.mesh().vertices;
  const auto& T_P = pair.P.mesh().triangles;
  const auto& T_S = pair.S.mesh().triangles;
  for (const ContactConstraint& old : in) {
    ContactConstraint c = old;
    Vector3 n, a, b;  // normal and a point of each feature's plane/line, in S
    switch (old.kind) {
      case FeaturePairKind::kVertexFace:
        n = pair.S.face_normals()[old.feature_S];
        a = pair.X_SP * V_P[old.feature_P] + q_S;
        b = V_S[T_S[old.feature_S][0]];
        c.p_S = a;
        break;
      case FeaturePairKind::kFaceVertex:
        n = -(pair.X_SP.R_SP * pair.P.face_normals()[old.feature_P]);
        a = pair.X_SP * V_P[T_P[old.feature_P][0]] + q_S;
        b = V_S[old.feature_S];
        c.p_S = b;
        break;
      case FeaturePairKind::kEdgeEdge: {
        const MeshEdge& e_P = pair.P.topology().edges[old.feature_P];
        const MeshEdge& e_S = pair.S.topology().edges[old.feature_S];
        a = pair.X_SP * V_P[e_P.v0] + q_S;
        const Vector3 a1 = pair.X_SP * V_P[e_P.v1] + q_S;
        b = V_S[e_S.v0];
        n = (a1 - a).cross(V_S[e_S.v1] - b);
        const double len = n.norm();
        if (len <= 0.0) continue;
        n /= len;
        c.p_S = 0.5 * (a + a1);
        break;
      }
    }
    if (n.dot(old.n_S) < 0) n = -n;  // keep the side chosen when the pair was found
    const double h = n.dot(a - b);
    c.n_S = n;
    c.c = n.dot(q_S) - h;
    out->push_back(c);
  }
}

}  // namespace pd
