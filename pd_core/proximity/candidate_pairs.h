#pragma once
// Verlet-style list of the BVH leaf pairs (or twig pairs, see Grain) of a
// probe and a scene object that
// lie within a distance (the radius) of one configuration, each with a lower
// bound on its boxes' gap there, sorted by that gap. A later configuration
// whose probe points all moved by at most D (rotation angle times radius plus
// the centre's motion) can only bring a listed pair within d if its gap is at
// most d + D: queries walk that prefix of the list alone, a few pairs near
// the contact instead of a descent of both hierarchies, and every pair that
// can touch is in the list while D + d stays below the radius.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "pd_core/proximity/bvh_pair_descent.h"
#include "pd_core/proximity/model_pair.h"

namespace pd {

// A twig of `levels` (>= 0): a leaf, or a node whose two children are twigs
// of levels - 1 (at most 2^levels leaves; one level: a node whose children
// are both leaves, up to 2 * Bvh::kMaxLeafTriangles triangles).
inline bool IsTwig(const std::vector<BvhNode>& nodes, int32_t i, int levels) {
  const BvhNode& n = nodes[i];
  if (n.is_leaf()) return true;
  return levels > 0 && IsTwig(nodes, i + 1, levels - 1) &&
         IsTwig(nodes, n.right_or_first, levels - 1);
}

class CandidatePairs {
 public:
  struct Entry {
    int32_t ip, is;  // leaf node indices (probe BVH, scene BVH)
    double gap;      // lower bound on the boxes' distance at the build configuration (m)
    // A separating direction of the two boxes at the build configuration
    // (unit, in S, pointing from the scene box to the probe box) and the
    // boxes' gap along it (m, <= gap). The probe moved by shift_S plus at
    // most a rotation's bound rot (see MotionSinceBuild) keeps its leaf's
    // contents at least axis_gap + axis_S . shift_S - rot from the scene
    // leaf's: a pair the motion slides along, not into, is proven apart
    // without a box test.
    Vector3 axis_S;
    double axis_gap;
    // True if, with the probe shifted by any point of the segment
    // [shift_a_S, shift_b_S] plus rotation bound rot (m) since the build,
    // the two leaves stay farther apart than `distance` along axis_S.
    bool StaysApart(const Vector3& shift_a_S, const Vector3& shift_b_S, double rot,
                    double distance) const {
      return axis_gap + std::min(axis_S.dot(shift_a_S), axis_S.dot(shift_b_S)) - rot > distance;
    }
  };

  CandidatePairs() { entries_.reserve(4096); }

  // What an entry pairs. Leaf pairs: a walk tests each entry it cannot skip
  // once. Twig pairs: a probe twig of kProbeTwigLevels with a scene twig of
  // kSceneTwigLevels (IsTwig); a build stops a level or two higher on each
  // side, where most of its box tests are (a leaf-pair list costs about five
  // per entry), and holds fewer entries; a walk descends each entry's two
  // subtrees at its own, much smaller distance (a few box tests).
  enum class Grain { kLeafPairs, kTwigPairs };
  // The scene side goes a level coarser than the probe's: on the benchmark's
  // densest haptic path (fandisk_elephant, haptic_work) p99 work 9930 ->
  // 8422 tests, max 24529 -> 23612, median 262 -> 264; 1 and 1 levels, 2 and
  // 2, 0 and 2 or 1 and 3 did no better (8253-10076 p99); the other pairs'
  // p99 within 1.3%.
  static constexpr int kProbeTwigLevels = 1, kSceneTwigLevels = 2;

  // Collects the node pairs of the grain whose boxes are within `radius` (m)
  // of each other with the probe at the pair's pose translated by q_center_S.
  void Build(const ModelPair& pair, const Vector3& q_center_S, double radius,
             Grain grain = Grain::kLeafPairs);

  // Build in pieces, for a real-time caller's idle time: BeginBuild takes
  // the configuration (no box tests), each ContinueBuild descends until the
  // list is complete (true: valid from then on) or pause() says stop (asked
  // every few dozen box tests; false: call again later, the pose may have
  // moved meanwhile). The list is invalid until complete; the entries, and
  // the box tests booked to `counters` (kListBuild), are those of Build.
  void BeginBuild(const ModelPair& pair, const Vector3& q_center_S, double radius,
                  Grain grain = Grain::kLeafPairs);
  bool ContinueBuild(const std::function<bool()>& pause, ProximityCounters* counters);
  // True while a BeginBuild has not completed.
  bool building() const { return building_; }
  // True if the configurations of `pair` translated by q_S, grown by
  // `extra` (m), lie within the reach of the list being built (as Covers
  // will say once it is complete).
  bool BuildWillCover(const ModelPair& pair, const Vector3& q_S, double extra) const;

  // Upper bound on how far any probe point is from where it was at the build
  // configuration, for `pair`'s pose translated by q_S (m); +inf when the
  // list is not this pair's or not valid.
  double Displacement(const ModelPair& pair, const Vector3& q_S) const;

  // True if every configuration of `pair` translated by a point of the
  // segment [q_a_S, q_b_S], grown by `extra` (m), lies within the budget.
  bool Covers(const ModelPair& pair, const Vector3& q_a_S, const Vector3& q_b_S,
              double extra) const;

  // For the sweep q_from_S + s * sweep_S: the largest s in [0, 1] up to which
  // every configuration (grown by `extra`) is covered, or a negative value
  // if the start is not covered.
  double CoveredFraction(const ModelPair& pair, const Vector3& q_from_S, const Vector3& sweep_S,
                         double extra) const;

  // How many leading entries can come within `distance` at configurations
  // displaced by at most `displacement` (the rest cannot).
  int NearCount(double distance, double displacement) const;

  // The motion of the probe since the build configuration, for `pair`'s
  // pose translated by q_S: every probe point moved by shift_S plus at most
  // *rotation_bound (m). False when the list is not this pair's or not valid.
  bool MotionSinceBuild(const ModelPair& pair, const Vector3& q_S, Vector3* shift_S,
                        double* rotation_bound) const;

  void Invalidate() {
    valid_ = false;
    building_ = false;
  }
  bool valid() const { return valid_; }
  Grain grain() const { return grain_; }
  double radius() const { return radius_; }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  // Rotation part of the displacement bound (m) and the centre's motion.
  void Motion(const ModelPair& pair, double* rotation_bound, Vector3* center_shift_S) const;
  // Displacement from the build configuration whether or not the list is
  // complete yet (+inf when it is not this pair's).
  double DisplacementFromBuild(const ModelPair& pair, const Vector3& q_S) const;
  bool valid_ = false;
  Grain grain_ = Grain::kLeafPairs;
  RelativePose X_SP_;
  Vector3 q_center_S_ = Vector3::Zero();
  double radius_ = 0.0;
  const CollisionModel* probe_ = nullptr;
  const CollisionModel* scene_ = nullptr;
  std::vector<Entry> entries_;
  bool building_ = false;  // a BeginBuild has not completed
  DescentCursor cursor_;   // where that build's descent stands
};

}  // namespace pd
