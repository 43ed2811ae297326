#include "pd_core/proximity/candidate_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pd_core/proximity/box_overlap.h"
#include "pd_core/proximity/bvh_pair_descent.h"

namespace pd {

void CandidatePairs::Build(const ModelPair& pair, const Vector3& q_center_S, double radius) {
  entries_.clear();
  X_SP_ = pair.X_SP;
  q_center_S_ = q_center_S;
  radius_ = radius;
  probe_ = &pair.P;
  scene_ = &pair.S;
  valid_ = true;
  ProbeBoxMemo probe_box(pair.X_SP, q_center_S);
  DescendBvhPair(
      pair.P.bvh(), pair.S.bvh(),
      [&](const BvhNode& a, const BvhNode& b, double* key) {
        *key = BoxGap(probe_box(a), b, radius);
        return *key <= radius;
      },
      [](double) { return true; },
      [&](int ip, int is, double gap) {
        entries_.push_back({ip, is, gap, Vector3::Zero(), 0.0});  // the node test's full bound
        return true;
      },
      pair.counters);
  // Each entry's separating direction: one more box computation per entry.
  const auto& nodes_P = pair.P.bvh().nodes();
  const auto& nodes_S = pair.S.bvh().nodes();
  for (Entry& e : entries_) {
    e.axis_gap = SeparatingAxisGap(probe_box(nodes_P[e.ip]), nodes_S[e.is], &e.axis_S);
  }
  if (pair.counters) pair.counters->box_tests += static_cast<int64_t>(entries_.size());
  std::sort(entries_.begin(), entries_.end(),
            [](const Entry& x, const Entry& y) { return x.gap < y.gap; });
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

double CandidatePairs::Displacement(const ModelPair& pair, const Vector3& q_S) const {
  if (!valid_ || probe_ != &pair.P || scene_ != &pair.S)
    return std::numeric_limits<double>::infinity();
  double rot;
  Vector3 shift;
  Motion(pair, &rot, &shift);
  return (shift + q_S).norm() + rot;
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
