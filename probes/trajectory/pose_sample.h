#pragma once
// One sample of a probe trajectory: pose of the tool frame P in world W at
// trajectory time t (s). Quaternions are w, x, y, z.
#include <array>
#include <vector>

namespace probes {

using Vec3 = std::array<double, 3>;
using Quat = std::array<double, 4>;  // w, x, y, z

struct PoseSample {
  double t = 0.0;                   // trajectory time (s)
  Vec3 p_WP{0.0, 0.0, 0.0};         // tool origin in world (m)
  Quat q_WP{1.0, 0.0, 0.0, 0.0};    // R_WP, unit quaternion w, x, y, z
  bool has_velocity = false;        // true when v_WP and w_WP are known
  Vec3 v_WP{0.0, 0.0, 0.0};         // linear velocity in world (m/s)
  Vec3 w_WP{0.0, 0.0, 0.0};         // angular velocity in world (rad/s)
};

using Trajectory = std::vector<PoseSample>;

}  // namespace probes
