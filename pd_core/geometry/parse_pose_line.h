#pragma once
// Parses one text line holding a pose "x y z qw qx qy qz": position of frame
// P in world W (metres) and the unit quaternion of R_WP, w first, separated
// by spaces or tabs. Blank lines and lines whose first non-blank character is
// '#' carry no pose.
#include <string>
#include <string_view>

#include "pd_core/geometry/pose.h"

namespace pd {

struct PoseLine {
  enum class Kind { kSkip, kPose, kError };
  Kind kind = Kind::kSkip;
  Isometry3 X_WP = Isometry3::Identity();  // meaningful when kind == kPose
  std::string error;                       // why the line was refused, when kError
};

// Refuses a wrong number of fields, non-numbers, NaN/inf, and quaternions
// whose norm is not within kQuaternionNormTol of 1 (so a zero quaternion is
// refused); accepted quaternions are normalised.
inline constexpr double kQuaternionNormTol = 1e-3;
PoseLine ParsePoseLine(std::string_view line);

}  // namespace pd
