#pragma once
// A probe model P posed in a scene model's frame S: the shared context of all
// pair queries. Every query takes an extra translation `offset_S` of the probe
// (expressed in S), the configuration-space point PolyDepth moves through.
#include <functional>

#include "pd_core/proximity/bvh_pair_descent.h"
#include "pd_core/mesh/collision_model.h"
#include "pd_core/geometry/relative_pose.h"

namespace pd {

class ProbeBoxCache;
class PlacedInnerSpheres;

class CandidatePairs;
class DescentFront;
struct IntersectionHint;
struct LeafPairRecord;

struct ModelPair {
  const CollisionModel& P;
  const CollisionModel& S;
  RelativePose X_SP;
  // Optional leaf-pair list of this pair (see candidate_pairs.h); queries
  // use it instead of descending the BVHs when it covers their configurations.
  const CandidatePairs* candidates = nullptr;
  // Optional leaf pairs recorded near one configuration by the last CCD or
  // localisation (see leaf_pair_record.h): used instead of a descent at the
  // configurations it answers for.
  const LeafPairRecord* recorded = nullptr;
  // Optional: where the last full descent (CCD, localisation, collision
  // test) ended (descent_front.h); the next one near there starts there and
  // replaces it.
  DescentFront* front = nullptr;
  // Optional: where the last of a series of collision tests expecting depth
  // found its surfaces crossing (mesh_collision.h); the next one looks
  // there first and moves it.
  IntersectionHint* intersection_hint = nullptr;
  // Optional: the probe's node boxes rotated into S (box_overlap.h), for
  // this pair's pose only.
  ProbeBoxCache* probe_boxes = nullptr;
  // Optional: the pair's inner spheres placed at this pair's rotation
  // (inner_sphere_overlap.h).
  PlacedInnerSpheres* inner_spheres = nullptr;
  // Optional cost accounting of the queries on this pair.
  ProximityCounters* counters = nullptr;
  // Optional: asked during a CCD's best-first descent; true ends it early
  // (a bounded-time caller's budget is spent). See translational_ccd.h.
  const std::function<bool()>* stop_ccd = nullptr;

  ModelPair(const CollisionModel& probe, const CollisionModel& scene, const Isometry3& X_WP,
            const Isometry3& X_WS)
      : P(probe), S(scene), X_SP(RelativePose::FromWorld(X_WS, X_WP)) {}

  // Probe vertex v in S at translation offset_S.
  Vector3 ProbeVertex(int v, const Vector3& offset_S) const {
    return X_SP * P.mesh().vertices[v] + offset_S;
  }
  // Scene vertex v in P's frame with the probe translated by offset_S:
  // R_SP^T (p_S - p_SP - offset_S).
  Vector3 SceneVertexInP(int v, const Vector3& offset_S) const {
    return X_SP.R_SP.transpose() * (S.mesh().vertices[v] - X_SP.p_SP - offset_S);
  }
  void ProbeTriangle(int t, const Vector3& offset_S, Vector3 out[3]) const {
    const auto& tri = P.mesh().triangles[t];
    for (int k = 0; k < 3; ++k) out[k] = ProbeVertex(tri[k], offset_S);
  }
  void SceneTriangle(int t, Vector3 out[3]) const {
    const auto& tri = S.mesh().triangles[t];
    for (int k = 0; k < 3; ++k) out[k] = S.mesh().vertices[tri[k]];
  }
  // Sum of bounding radii: the length that relative tolerances multiply.
  double size() const { return P.radius() + S.radius(); }
};

}  // namespace pd
