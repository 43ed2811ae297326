#pragma once
// Collision certificate from the models' inner spheres (inner_spheres.h):
// an open ball inside the probe's solid overlapping one inside the scene's
// proves the solids overlap, with no BVH test. Deep configurations (a cold
// search's probes well inside its best answer) are mostly settled this way;
// shallow ones never are (the spheres keep clear of the surfaces), so only
// callers that expect depth ask.
#include <array>

#include "pd_core/proximity/model_pair.h"

namespace pd {

// A pair's inner spheres at one probe rotation, as columns of coordinates:
// the probe's centres rotated into S (the translation is added per query)
// and the scene's. The check of one probe sphere against all the scene's is
// then a loop the compiler vectorises (same verdicts: the same sums in the
// same order, no early exit inside the loop; cold queries -4%). Fixed
// capacity, no allocation; models with more spheres than it holds (more
// than ComputeInnerSpheres makes by default) take the unplaced check.
class PlacedInnerSpheres {
 public:
  static constexpr int kCapacity = 64;
  // Forgets the placement (a new probe pose).
  void Invalidate() { placed_ = false; }
  // Places the pair's spheres unless placed since the last Invalidate;
  // false if either model has more than kCapacity.
  bool PlaceOnce(const ModelPair& pair);
  // InnerSpheresOverlap on the placement (PlaceOnce true).
  bool Overlap(const ModelPair& pair, const Vector3& offset_S) const;

 private:
  bool placed_ = false;
  bool fits_ = false;
  int n_P_ = 0, n_S_ = 0;
  // Probe: centre at the rotation (R_SP p_MC) and radius; scene: centre and radius.
  std::array<double, kCapacity> px_, py_, pz_, pr_, sx_, sy_, sz_, sr_;
};

// True if an inner sphere of the probe, translated by offset_S (m, in S),
// overlaps an inner sphere of the scene (false, not a verdict, otherwise).
// Counts one box test per probe sphere placed (its distance checks against
// all the scene's spheres cost about one box test).
bool InnerSpheresOverlap(const ModelPair& pair, const Vector3& offset_S);

}  // namespace pd
