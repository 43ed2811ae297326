#pragma once
// Contact-space localisation: the feature pairs (vertex-face, face-vertex,
// edge-edge) of a probe and a scene object that lie within a distance, each
// turned into a half-space n·q >= c on the probe translation q (in S). The
// half-spaces are necessary conditions for freedom near the configuration,
// so their intersection is a conservative local model of free space.
#include <cstdint>
#include <vector>

#include "pd_core/model_pair.h"

namespace pd {

enum class FeaturePairKind : uint8_t { kVertexFace, kFaceVertex, kEdgeEdge };

struct ContactConstraint {
  Vector3 n_S;     // unit; moving the probe along +n separates the pair
  double c = 0.0;  // the probe translation q_S must satisfy n·q >= c (m)
  Vector3 p_S;     // contact point on the probe at the configuration (m, in S)
  FeaturePairKind kind = FeaturePairKind::kVertexFace;
};

// Appends (after clearing) the constraints of all feature pairs closer than
// `distance` (m) with the probe translated by q_S. The configuration is
// expected to be collision-free (a point on or near the contact space).
void CollectContactConstraints(const ModelPair& pair, const Vector3& q_S, double distance,
                               std::vector<ContactConstraint>* out);

}  // namespace pd
