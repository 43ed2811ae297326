#pragma once
// Verlet-style list of the BVH leaf pairs of a probe and a scene object that
// lie within a distance of one configuration. While later configurations stay
// within that distance budget (bounded by the probe's displacement: rotation
// angle times radius plus the centre's motion), every triangle pair that can
// touch there is in the list, so queries loop over a few dozen pairs instead
// of descending both hierarchies. This is what makes a warm-started haptic
// query cost microseconds: the probe moves ~1e-4 of its size per tick.
#include <utility>
#include <vector>

#include "pd_core/model_pair.h"

namespace pd {

class CandidatePairs {
 public:
  CandidatePairs() { leaf_pairs_.reserve(4096); }

  // Collects leaf pairs whose boxes are within `radius` (m) of each other
  // with the probe at the pair's pose translated by q_center_S.
  void Build(const ModelPair& pair, const Vector3& q_center_S, double radius);

  // True if every configuration of `pair` translated by a point of the
  // segment [q_a_S, q_b_S], grown by `extra` (m), lies within the budget.
  bool Covers(const ModelPair& pair, const Vector3& q_a_S, const Vector3& q_b_S,
              double extra) const;

  // For the sweep q_from_S + s * sweep_S: the largest s in [0, 1] up to which
  // every configuration (grown by `extra`) is covered, or a negative value
  // if the start is not covered.
  double CoveredFraction(const ModelPair& pair, const Vector3& q_from_S, const Vector3& sweep_S,
                         double extra) const;

  void Invalidate() { valid_ = false; }
  bool valid() const { return valid_; }
  // Leaf node indices (probe BVH, scene BVH).
  const std::vector<std::pair<int, int>>& leaf_pairs() const { return leaf_pairs_; }

 private:
  double Displacement(const ModelPair& pair, const Vector3& q_S) const;
  // Rotation part of the displacement bound (m) and the centre's motion.
  void Motion(const ModelPair& pair, double* rotation_bound, Vector3* center_shift_S) const;
  bool valid_ = false;
  RelativePose X_SP_;
  Vector3 q_center_S_ = Vector3::Zero();
  double radius_ = 0.0;
  const CollisionModel* probe_ = nullptr;
  const CollisionModel* scene_ = nullptr;
  std::vector<std::pair<int, int>> leaf_pairs_;
};

}  // namespace pd
