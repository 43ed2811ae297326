#include "probes/trajectory/motion_path.h"

#include <algorithm>
#include <cmath>

namespace probes {
namespace {

// Minimum-jerk profile s(u) on [0, 1] and its derivative ds/du.
double MinJerk(double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }
double MinJerkRate(double u) { return 30.0 * u * u * (1.0 - u) * (1.0 - u); }

double Distance(const Vec3& a, const Vec3& b) {
  return std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                   (b[2] - a[2]) * (b[2] - a[2]));
}

}  // namespace

double MotionPath::MoveTime(const Vec3& from, const Vec3& to, double speed) {
  return Distance(from, to) / speed;
}

void MotionPath::MoveTo(const Vec3& to, double speed) {
  const double T = MoveTime(end_, to, speed);
  if (T <= 0.0) return;
  Piece piece{Piece::Kind::kMove, duration_, T, end_, to, {}, 0.0, 0.0, 0.0};
  pieces_.push_back(piece);
  duration_ += T;
  end_ = to;
}

void MotionPath::Hold(double duration) {
  if (duration <= 0.0) return;
  pieces_.push_back({Piece::Kind::kHold, duration_, duration, end_, end_, {}, 0.0, 0.0, 0.0});
  duration_ += duration;
}

void MotionPath::Circle(const Vec3& axis_point, int turns, double speed) {
  const double dx = end_[0] - axis_point[0];
  const double dy = end_[1] - axis_point[1];
  const double radius = std::hypot(dx, dy);
  if (turns <= 0 || radius <= 0.0) return;
  const double sweep = 2.0 * M_PI * turns;
  const double T = radius * sweep / speed;
  pieces_.push_back({Piece::Kind::kCircle, duration_, T, end_, end_, axis_point, radius,
                     std::atan2(dy, dx), sweep});
  duration_ += T;
}

void MotionPath::Evaluate(double t, Vec3* p, Vec3* v) const {
  *v = {0.0, 0.0, 0.0};
  if (pieces_.empty()) {
    *p = end_;
    return;
  }
  t = std::clamp(t, 0.0, duration_);
  // Last piece starting at or before t (pieces are few: a linear scan is fine).
  const Piece* piece = &pieces_.front();
  for (const Piece& candidate : pieces_) {
    if (candidate.t0 <= t) piece = &candidate;
  }
  const double u = std::clamp((t - piece->t0) / piece->duration, 0.0, 1.0);
  const double s = MinJerk(u);
  const double s_dot = MinJerkRate(u) / piece->duration;
  switch (piece->kind) {
    case Piece::Kind::kHold:
      *p = piece->from;
      break;
    case Piece::Kind::kMove:
      for (int i = 0; i < 3; ++i) {
        const double delta = piece->to[i] - piece->from[i];
        (*p)[i] = piece->from[i] + delta * s;
        (*v)[i] = delta * s_dot;
      }
      break;
    case Piece::Kind::kCircle: {
      // Minimum-jerk in angle: starts and stops at rest like the moves.
      const double angle = piece->phase0 + piece->sweep * s;
      const double rate = piece->sweep * s_dot;
      *p = {piece->axis_point[0] + piece->radius * std::cos(angle),
            piece->axis_point[1] + piece->radius * std::sin(angle), piece->from[2]};
      *v = {-piece->radius * std::sin(angle) * rate, piece->radius * std::cos(angle) * rate, 0.0};
      break;
    }
  }
}

}  // namespace probes
