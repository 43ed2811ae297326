#include "pd_core/candidate_pairs.h"

#include <algorithm>
#include <cmath>

#include "pd_core/box_overlap.h"

namespace pd {

void CandidatePairs::Build(const ModelPair& pair, const Vector3& q_center_S, double radius) {
  leaf_pairs_.clear();
  X_SP_ = pair.X_SP;
  q_center_S_ = q_center_S;
  radius_ = radius;
  probe_ = &pair.P;
  scene_ = &pair.S;
  valid_ = true;
  const Bvh& bvh_P = pair.P.bvh();
  const Bvh& bvh_S = pair.S.bvh();
  if (bvh_P.empty() || bvh_S.empty()) return;
  const auto& nodes_P = bvh_P.nodes();
  const auto& nodes_S = bvh_S.nodes();
  std::pair<int, int> stack[256];
  int top = 0;
  stack[top++] = {0, 0};
  while (top > 0) {
    const auto [ip, is] = stack[--top];
    const BvhNode& a = nodes_P[ip];
    const BvhNode& b = nodes_S[is];
    if (!BoxesWithin(ProbeBox(a, pair.X_SP, q_center_S), b, radius)) continue;
    if (a.is_leaf() && b.is_leaf()) {
      leaf_pairs_.emplace_back(ip, is);
      continue;
    }
    if (b.is_leaf() || (!a.is_leaf() && NodeSize2(a) >= NodeSize2(b))) {
      stack[top++] = {a.right_or_first, is};
      stack[top++] = {ip + 1, is};
    } else {
      stack[top++] = {ip, b.right_or_first};
      stack[top++] = {ip, is + 1};
    }
  }
}

// Upper bound on how far any probe point moved between the build
// configuration and (pair pose, translation q_S).
void CandidatePairs::Motion(const ModelPair& pair, double* rotation_bound,
                            Vector3* center_shift_S) const {
  const Vector3& c_P = pair.P.center();
  *rotation_bound = RotationAngleBetween(X_SP_.R_SP, pair.X_SP.R_SP) * pair.P.radius();
  *center_shift_S = (pair.X_SP * c_P) - (X_SP_ * c_P + q_center_S_);
}

double CandidatePairs::Displacement(const ModelPair& pair, const Vector3& q_S) const {
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
  if (!valid_ || probe_ != &pair.P || scene_ != &pair.S) return false;
  // |displacement| is convex along the segment: the endpoints bound it.
  return std::max(Displacement(pair, q_a_S), Displacement(pair, q_b_S)) + extra < radius_;
}

}  // namespace pd
