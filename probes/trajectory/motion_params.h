#pragma once
// Parameters of a scripted probe motion (probe_sim). SI units; positions are
// of the tool origin P in world W, which stays at the constant orientation.
//
//   script       approach_and_press | slide | stir | insert_peg
//   centre       reference point (m): where the tool origin is when it just
//                touches the surface (press, slide), the cup axis at the rim
//                (stir), the hole axis at the hole's top face (insert_peg)
//   amplitude    (m) press: height above centre where each press starts;
//                slide: half length of the stroke along `direction`;
//                stir: circle radius; insert_peg: radius of the circular
//                wiggle at the bottom (0 = straight in and out)
//   depth        (m) how far below centre the motion goes
//   speed        (m/s) average speed of each move (peak is 1.875x: the
//                moves follow minimum-jerk profiles)
//   duration     (s) total length; whole cycles are repeated to fill it
//   approach     (m) slide, stir, insert_peg: height above centre where the
//                motion starts and ends
//   hold         (s) pause at the bottom and top of every cycle
//   direction    slide direction (unit vector after normalising)
//   orientation  R_WP as w, x, y, z
//   rate_hz      sample rate
#include <string>

#include "probes/trajectory/pose_sample.h"

namespace probes {

struct MotionParams {
  std::string script;
  Vec3 centre{0.0, 0.0, 0.0};
  double amplitude = 0.02;
  double depth = 0.005;
  double speed = 0.02;
  double duration = 10.0;
  double approach = 0.02;
  double hold = 0.5;
  Vec3 direction{1.0, 0.0, 0.0};
  Quat orientation{1.0, 0.0, 0.0, 0.0};
  double rate_hz = 1000.0;
};

inline constexpr const char* kScriptNames = "approach_and_press, slide, stir, insert_peg";

// Overwrites the fields present in a YAML mapping file (keys as above).
// Throws InputError naming the file, line and key for an unknown key, a
// value of the wrong type or shape, or a file that cannot be parsed.
void LoadMotionParamsYaml(const std::string& path, MotionParams* params);

// Checks ranges and the script name; normalises direction and orientation.
// Throws InputError naming the field and value.
void ValidateMotionParams(MotionParams* params);

}  // namespace probes
