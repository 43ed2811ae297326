#pragma once
// Boolean collision of a probe against a scene object: surfaces intersect, or
// one closed solid holds the other (a probe wholly inside counts as colliding).
#include <array>

#include "pd_core/proximity/model_pair.h"

namespace pd {

// A triangle pair (probe, scene) that intersected at some earlier query:
// tested first by the next one, which then usually answers "colliding" with
// a single triangle test (the contact moves little between haptic ticks).
struct CollisionWitness {
  int tp = -1, ts = -1;
};

// Whether the witness pair or one of its edge-neighbour pairs intersects with
// the probe moved by offset_S (at most 16 triangle tests, no descent); on a
// hit the witness moves to the intersecting pair. False says nothing about
// the other pairs.
bool WitnessIntersects(const ModelPair& pair, const Vector3& offset_S,
                       CollisionWitness* witness);

// Any probe triangle intersecting any scene triangle, probe moved by
// offset_S. `witness` (optional) is tried first and updated on a hit. With
// `earlier`, those num_earlier pairs are tried before it (each as a witness,
// on the same placed probe triangles; `witness` must then be given): the
// intersecting pair found, by them or after, goes to *witness.
bool SurfacesIntersect(const ModelPair& pair, const Vector3& offset_S,
                       CollisionWitness* witness = nullptr,
                       const CollisionWitness* earlier = nullptr, int num_earlier = 0);

// SurfacesIntersect, or a part of one mesh inside the other's solid, either
// way, for closed meshes (pd_core/proximity/solid_containment.h).
bool InCollision(const ModelPair& pair, const Vector3& offset_S,
                 CollisionWitness* witness = nullptr, const CollisionWitness* earlier = nullptr,
                 int num_earlier = 0);

// Where the last few of a series of collision tests found the surfaces
// crossing: node pairs (probe BVH node, scene BVH node) some levels above
// each crossing's leaf pair, the most recent first. Consecutive tests of a
// cold search (its landing thresholds and probes, far apart in direction
// but all around one query) mostly cross the surfaces in one of a few
// regions: a descent below one of these reaches an intersecting pair in
// fewer tests than one from the roots.
struct IntersectionHint {
  static constexpr int kCapacity = 4;
  std::array<NodePair, kCapacity> regions;
  int size = 0;
  void Invalidate() { size = 0; }
  // Puts `region` first (it was regions[from], or new when from == size).
  void MoveToFront(int from, NodePair region);
};

// InCollision for a configuration expected to lie deep inside (a cold
// search's landing thresholds and inner probes): the models' inner spheres
// overlapping settle most of those with no BVH test (inner_sphere_overlap.h);
// the rest take InCollision, descending first below the regions of
// pair.intersection_hint (when set; then from the roots) and moving the
// region where the surfaces crossed to its front. The same verdict either
// way.
bool InCollisionExpectingDepth(const ModelPair& pair, const Vector3& offset_S);

}  // namespace pd
