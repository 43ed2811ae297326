#pragma once
// Contact-space localisation: the feature pairs (vertex-face, face-vertex,
// edge-edge) of a probe and a scene object that lie within a distance, each
// turned into a half-space n·q >= c on the probe translation q (in S). The
// half-spaces are necessary conditions for freedom near the configuration,
// so their intersection is a conservative local model of free space.
#include <cstdint>
#include <vector>

#include "pd_core/proximity/leaf_pair_record.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

namespace pd {

enum class FeaturePairKind : uint8_t { kVertexFace, kFaceVertex, kEdgeEdge };

struct ContactConstraint {
  Vector3 n_S;     // unit; moving the probe along +n separates the pair
  double c = 0.0;  // the probe translation q_S must satisfy n·q >= c (m)
  Vector3 p_S;     // contact point on the probe at the configuration (m, in S)
  FeaturePairKind kind = FeaturePairKind::kVertexFace;
  // The features: vertex-face: probe vertex, scene triangle; face-vertex:
  // probe triangle, scene vertex; edge-edge: probe edge, scene edge (indices
  // into each model's topology().edges).
  int32_t feature_P = -1, feature_S = -1;
  // The triangle pair (probe, scene) the features were found on: a witness
  // to try first where the half-space is violated (mesh_collision.h).
  int32_t tri_P = -1, tri_S = -1;
};

// Appends (after clearing) the constraints of all feature pairs closer than
// `distance` (m) with the probe translated by q_S. The configuration is
// expected to be collision-free (a point on or near the contact space).
// With `record` (unless it covers q_S for `distance` already), the leaf
// pairs within max(distance, record->distance) of each other at q_S are
// recorded there (leaf_pair_record.h): the tests just off this
// configuration walk them instead of descending.
void CollectContactConstraints(const ModelPair& pair, const Vector3& q_S, double distance,
                               std::vector<ContactConstraint>* out,
                               LeafPairRecord* record = nullptr);

// Localisation fused with the surface-intersection test at the same
// configuration (one pass over the same leaf pairs): returns false, with
// `out` incomplete (and `record` invalid), as soon as a probe triangle
// intersects a scene triangle (recorded in *witness if given); otherwise
// collects like CollectContactConstraints and returns true. Containment is
// not tested.
bool CollectContactConstraintsIfSurfacesFree(const ModelPair& pair, const Vector3& q_S,
                                             double distance,
                                             std::vector<ContactConstraint>* out,
                                             CollisionWitness* witness = nullptr,
                                             LeafPairRecord* record = nullptr);

// The same feature pairs as `in` (collected at an earlier pose of the pair),
// their half-spaces re-evaluated at the pair's current pose with the probe
// translated by q_S; each normal keeps the side it had in `in`. A prediction
// of the contact's local model after a small motion, for warm starts: it is
// exact for these features but may miss features that came into reach.
void RefreshContactConstraints(const ModelPair& pair, const Vector3& q_S,
                               const std::vector<ContactConstraint>& in,
                               std::vector<ContactConstraint>* out);

}  // namespace pd
