#pragma once
// A piecewise path of the tool origin built from minimum-jerk moves, holds
// and circular arcs. Every piece starts and ends at rest, so position,
// velocity and acceleration are continuous across pieces: the device stand-in
// never asks the server to render an impossible jump.
#include <vector>

#include "probes/trajectory/pose_sample.h"

namespace probes {

class MotionPath {
 public:
  explicit MotionPath(const Vec3& start) : end_(start) {}

  // Straight line to `to` at average speed `speed` (m/s).
  void MoveTo(const Vec3& to, double speed);
  // Stays at the current point.
  void Hold(double duration);
  // `turns` full circles (counter-clockwise about +z) around `axis_point` in
  // the horizontal plane of the current point, starting at the current
  // point, at average tangential speed `speed`. The radius is the current
  // point's horizontal distance from axis_point.
  void Circle(const Vec3& axis_point, int turns, double speed);

  double duration() const { return duration_; }
  const Vec3& end() const { return end_; }

  // Position and velocity at time t (clamped to [0, duration]).
  void Evaluate(double t, Vec3* p, Vec3* v) const;

  // Time a move of this length takes at this speed, for planning.
  static double MoveTime(const Vec3& from, const Vec3& to, double speed);

 private:
  struct Piece {
    enum class Kind { kMove, kHold, kCircle } kind;
    double t0;
    double duration;
    Vec3 from;
    Vec3 to;          // kMove
    Vec3 axis_point;  // kCircle
    double radius;    // kCircle
    double phase0;    // kCircle: start angle (rad)
    double sweep;     // kCircle: total angle (rad)
  };
  std::vector<Piece> pieces_;
  Vec3 end_;
  double duration_ = 0.0;
};

}  // namespace probes
