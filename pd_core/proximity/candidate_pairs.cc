#include "pd_core/proximity/candidate_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pd_core/proximity/box_overlap.h"

namespace pd {

namespace {
// Leaf pairs nearer than this many radii along the face axes get every axis
// at a build. The walks reach the farther ones only late in the list's life
// (their prefix grows with the motion since the build), where the sharper
// gap saved less than it cost: on the benchmark's haptic paths all axes on
// every leaf pair made rebuilds set p99 ~10% higher (knot1_bunny 686 -> 629
// us, fandisk_elephant 1589 -> 1450 at 0.3), with the medians unchanged.
constexpr double kFullTestGap = 0.25;
constexpr double kNoEarlyExit = std::numeric_limits<double>::infinity();
}  // namespace

void CandidatePairs::Build(const ModelPair& pair, const Vector3& q_center_S, double radius,
                           Grain grain) {
  BeginBuild(pair, q_center_S, radius, grain);
  ContinueBuild([] { return false; }, pair.counters);
}

void CandidatePairs::BeginBuild(const ModelPair& pair, const Vector3& q_center_S,
                                double radius, Grain grain) {
  entries_.clear();
  X_SP_ = pair.X_SP;
  q_center_S_ = q_center_S;
  radius_ = radius;
  probe_ = &pair.P;
  scene_ = &pair.S;
  valid_ = false;
  building_ = true;
  grain_ = grain;
  cursor_.Reset();
}

bool CandidatePairs::BuildWillCover(const ModelPair& pair, const Vector3& q_S,
                                    double extra) const {
  return building_ && DisplacementFromBuild(pair, q_S) + extra < radius_;
}

bool CandidatePairs::ContinueBuild(const std::function<bool()>& pause,
                                   ProximityCounters* counters) {
  if (!building_) return valid_;
  WorkScope scope(counters, QueryKind::kListBuild);
  const double radius = radius_;
  const Grain grain = grain_;
  ProbeBoxMemo probe_box(X_SP_, q_center_S_);
  const Bvh& bvh_P = probe_->bvh();
  const Bvh& bvh_S = scene_->bvh();
  const auto& nodes_P = bvh_P.nodes();
  const auto& nodes_S = bvh_S.nodes();
  int64_t full_tests = 0;
  // pause() is asked every kPauseStride pairs visited (a few us of work).
  constexpr int kPauseStride = 32;
  int visits = 0;
  // The descent prunes on the six face axes only (no edge-edge axes, no
  // sphere roots): kept pairs, most of those tested, would pay for all of
  // them. An entry's pair is tested once, where the descent reaches it: its
  // face axes give its gap and separating direction together (testing it in
  // the descent and again at its visit repeated the face axes on every kept
  // leaf pair: 10-14% of a build's box tests on the benchmark's haptic paths,
  // same lists). One nearer than kFullTestGap radii along them gets every
  // axis. The descent never goes below an entry's pair.
  const bool complete = ContinueBvhPairDescent(
      bvh_P, bvh_S,
      [&](const BvhNode& a, const BvhNode& b, double* key) {
        const int32_t ip = static_cast<int32_t>(&a - nodes_P.data());
        const int32_t is = static_cast<int32_t>(&b - nodes_S.data());
        const bool entry = grain == Grain::kTwigPairs
                               ? IsTwig(nodes_P, ip, kProbeTwigLevels) &&
                                     IsTwig(nodes_S, is, kSceneTwigLevels)
                               : a.is_leaf() && b.is_leaf();
        if (!entry) {
          *key = AxisGap<BoxAxes::kFaces>(probe_box(a), b, radius);  // nearer first
          return *key <= radius;
        }
        const ProbeBoxInS& box_a = probe_box(a);
        Vector3 axis_S;
        const double face_gap = AxisGap<BoxAxes::kFaces, true>(box_a, b, kNoEarlyExit, &axis_S);
        if (face_gap > radius) return false;
        double axis_gap = face_gap, gap = face_gap;
        if (face_gap <= kFullTestGap * radius) {
          ++full_tests;
          axis_gap = SeparatingAxisGap(box_a, b, &axis_S, radius);
          gap = std::max(axis_gap, SphereGap(box_a, b));
        }
        if (gap <= radius) entries_.push_back({ip, is, gap, axis_S, axis_gap});
        return false;
      },
      [](int, int) { return true; },
      [&] { return ++visits % kPauseStride == 0 && pause(); }, &cursor_, counters);
  if (counters) counters->box_tests += full_tests;
  if (!complete) return false;
  std::sort(entries_.begin(), entries_.end(),
            [](const Entry& x, const Entry& y) { return x.gap < y.gap; });
  valid_ = true;
  building_ = false;
  return true;
}

int CandidatePairs::NearCount(double distance, double displacement) const {
  const double limit = distance + displacement;
  const auto it = std::upper_bound(entries_.begin(), entries_.end(), limit,
                                   [](double v, const Entry& e) { return v < e.gap; });
  return static_cast<int>(it - entries_.begin());
}

// Upper bound on how far any probe point moved between the build
// configuration and (pair pose, translation q_S).
void CandidatePairs::Motion(const ModelPair& pair, double* rotation_bound,
                            Vector3* center_shift_S) const {
  const Vector3& c_P = pair.P.center();
  *rotation_bound = RotationAngleBetween(X_SP_.R_SP, pair.X_SP.R_SP) * pair.P.radius();
  *center_shift_S = (pair.X_SP * c_P) - (X_SP_ * c_P + q_center_S_);
}

bool CandidatePairs::MotionSinceBuild(const ModelPair& pair, const Vector3& q_S,
                                      Vector3* shift_S, double* rotation_bound) const {
  if (!valid_ || probe_ != &pair.P || scene_ != &pair.S) return false;
  Motion(pair, rotation_bound, shift_S);
  *shift_S += q_S;
  return true;
}

double CandidatePairs::DisplacementFromBuild(const ModelPair& pair, const Vector3& q_S) const {
  if (probe_ != &pair.P || scene_ != &pair.S) return std::numeric_limits<double>::infinity();
  double rot;
  Vector3 shift;
  Motion(pair, &rot, &shift);
  return (shift + q_S).norm() + rot;
}

double CandidatePairs::Displacement(const ModelPair& pair, const Vector3& q_S) const {
  return valid_ ? DisplacementFromBuild(pair, q_S) : std::numeric_limits<double>::infinity();
}

double CandidatePairs::CoveredFraction(const ModelPair& pair, const Vector3& q_from_S,
                                       const Vector3& sweep_S, double extra) const {
  if (!valid_ || probe_ != &pair.P || scene_ != &pair.S) return -1.0;
  double rot;
  Vector3 shift;
  Motion(pair, &rot, &shift);
  // Covered where |shift + q_from + s*sweep| < radius - rot - extra: a ball.
  const double r = radius_ - rot - extra;
  const Vector3 c = shift + q_from_S;
  if (r <= 0 || c.norm() >= r) return -1.0;
  const double a = sweep_S.squaredNorm();
  if (a <= 0) return 1.0;
  const double b = c.dot(sweep_S), cc = c.squaredNorm() - r * r;  // cc < 0
  const double s1 = (-b + std::sqrt(b * b - a * cc)) / a;
  return std::min(1.0, s1 * (1.0 - 1e-12));
}

bool CandidatePairs::Covers(const ModelPair& pair, const Vector3& q_a_S, const Vector3& q_b_S,
                            double extra) const {
  // |displacement| is convex along the segment: the endpoints bound it.
  return std::max(Displacement(pair, q_a_S), Displacement(pair, q_b_S)) + extra < radius_;
}

}  // namespace pd
