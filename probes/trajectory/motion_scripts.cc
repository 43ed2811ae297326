#include "probes/trajectory/motion_scripts.h"

#include <cmath>
#include <string>

#include "probes/trajectory/input_error.h"

namespace probes {
namespace {

Vec3 Add(const Vec3& a, const Vec3& b, double scale = 1.0) {
  return {a[0] + scale * b[0], a[1] + scale * b[1], a[2] + scale * b[2]};
}

constexpr Vec3 kUp{0.0, 0.0, 1.0};
constexpr Vec3 kX{1.0, 0.0, 0.0};

int FitCount(const MotionParams& p, double fixed_s, double cycle_s) {
  const int n = static_cast<int>(std::floor((p.duration - fixed_s) / cycle_s + 1e-9));
  if (n < 1) {
    throw InputError("motion parameter 'duration' = " + std::to_string(p.duration) +
                     " s is too short for one " + p.script + " cycle (needs " +
                     std::to_string(fixed_s + cycle_s) + " s with these parameters)");
  }
  return n;
}

MotionPath Press(const MotionParams& p) {
  const Vec3 top = Add(p.centre, kUp, p.amplitude);
  const Vec3 bottom = Add(p.centre, kUp, -p.depth);
  const double cycle = 2.0 * p.hold + 2.0 * MotionPath::MoveTime(top, bottom, p.speed);
  const int n = FitCount(p, 0.0, cycle);
  MotionPath path(top);
  for (int i = 0; i < n; ++i) {
    path.Hold(p.hold);
    path.MoveTo(bottom, p.speed);
    path.Hold(p.hold);
    path.MoveTo(top, p.speed);
  }
  return path;
}

MotionPath Slide(const MotionParams& p) {
  const Vec3 a = Add(p.centre, p.direction, -p.amplitude);
  const Vec3 b = Add(p.centre, p.direction, p.amplitude);
  const Vec3 a_top = Add(a, kUp, p.approach);
  const Vec3 a_low = Add(a, kUp, -p.depth);
  const Vec3 b_low = Add(b, kUp, -p.depth);
  const double fixed = 3.0 * p.hold + 2.0 * MotionPath::MoveTime(a_top, a_low, p.speed);
  const int strokes = FitCount(p, fixed, MotionPath::MoveTime(a_low, b_low, p.speed));
  MotionPath path(a_top);
  path.Hold(p.hold);
  path.MoveTo(a_low, p.speed);
  path.Hold(p.hold);
  for (int i = 0; i < strokes; ++i) path.MoveTo(i % 2 == 0 ? b_low : a_low, p.speed);
  path.Hold(p.hold);
  path.MoveTo(Add(path.end(), kUp, p.approach + p.depth), p.speed);
  return path;
}

MotionPath Stir(const MotionParams& p) {
  const Vec3 top = Add(p.centre, kUp, p.approach);
  const Vec3 low = Add(p.centre, kUp, -p.depth);
  const Vec3 rim = Add(low, kX, p.amplitude);
  const double fixed = p.hold + 2.0 * MotionPath::MoveTime(top, low, p.speed) +
                       2.0 * MotionPath::MoveTime(low, rim, p.speed);
  const int turns = FitCount(p, fixed, 2.0 * M_PI * p.amplitude / p.speed);
  MotionPath path(top);
  path.Hold(p.hold);
  path.MoveTo(low, p.speed);
  path.MoveTo(rim, p.speed);
  path.Circle(low, turns, p.speed);
  path.MoveTo(low, p.speed);
  path.MoveTo(top, p.speed);
  return path;
}

MotionPath InsertPeg(const MotionParams& p) {
  const Vec3 top = Add(p.centre, kUp, p.approach);
  const Vec3 bottom = Add(p.centre, kUp, -p.depth);
  const Vec3 wiggle_start = Add(bottom, kX, p.amplitude);
  double cycle = 2.0 * p.hold + 2.0 * MotionPath::MoveTime(top, bottom, p.speed);
  if (p.amplitude > 0.0) {
    cycle += 2.0 * MotionPath::MoveTime(bottom, wiggle_start, p.speed) +
             2.0 * M_PI * p.amplitude / p.speed;
  }
  const int n = FitCount(p, 0.0, cycle);
  MotionPath path(top);
  for (int i = 0; i < n; ++i) {
    path.Hold(p.hold);
    path.MoveTo(bottom, p.speed);
    if (p.amplitude > 0.0) {
      path.MoveTo(wiggle_start, p.speed);
      path.Circle(bottom, 1, p.speed);
      path.MoveTo(bottom, p.speed);
    }
    path.Hold(p.hold);
    path.MoveTo(top, p.speed);
  }
  return path;
}

}  // namespace

MotionPath BuildMotionPath(const MotionParams& p) {
  if (p.script == "approach_and_press") return Press(p);
  if (p.script == "slide") return Slide(p);
  if (p.script == "stir") return Stir(p);
  if (p.script == "insert_peg") return InsertPeg(p);
  throw InputError("motion parameter 'script' = '" + p.script + "' is not one of: " +
                   kScriptNames);
}

Trajectory SampleMotion(const MotionParams& p) {
  const MotionPath path = BuildMotionPath(p);
  const auto count = static_cast<size_t>(std::floor(p.duration * p.rate_hz + 1e-9));
  Trajectory trajectory(count);
  for (size_t k = 0; k < count; ++k) {
    PoseSample& s = trajectory[k];
    s.t = static_cast<double>(k) / p.rate_hz;
    path.Evaluate(s.t, &s.p_WP, &s.v_WP);
    s.q_WP = p.orientation;
    s.has_velocity = true;  // analytic: angular velocity is zero, orientation is constant
  }
  return trajectory;
}

}  // namespace probes
