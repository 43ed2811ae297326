#pragma once
// Helpers shared by the PD tests: poses (and poses from table rows), random
// rotations, the reference settings bench_pd scores haptic paths with, and
// the slow reference PD on tessellations of any geometry (a half-space
// stands in as a large box whose top face is z = 0).
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "pd_core/geometry/geometry.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/reference/reference_pd.h"
#include "pd_core/geometry/tessellate_geometry.h"

namespace pd {
namespace test {

inline Isometry3 Pose(const Vector3& p, const Quaternion& q = Quaternion::Identity()) {
  Isometry3 X = Isometry3::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = p;
  return X;
}

// A pose from a row of a recorded path: x y z (m), qw qx qy qz.
inline Isometry3 PoseOfRow(const std::array<double, 7>& p) {
  return Pose(Vector3(p[0], p[1], p[2]), Quaternion(p[3], p[4], p[5], p[6]));
}

// The reference settings of bench_pd's haptic scenario (128 directions, 4
// refinement starts of 24 evaluations each).
inline ReferencePdOptions BenchHapticReferenceOptions() {
  ReferencePdOptions ro;
  ro.num_directions = 128;
  ro.num_refine_starts = 4;
  ro.refine_iterations = 24;
  return ro;
}

inline Quaternion RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  return Quaternion(N(rng), N(rng), N(rng), N(rng)).normalized();
}

// A mesh of `g` and the pose that places it like g at X_WG: tessellation for
// bounded kinds; for the half-space a box of half size `big` below z = 0.
struct MeshStandIn {
  TriangleMesh mesh;
  Isometry3 X_WM;
};
inline MeshStandIn StandIn(const Geometry& g, const Isometry3& X_WG, double rel_chord_error,
                           double big) {
  if (g.bounded()) return {TessellateGeometry(g, rel_chord_error), X_WG};
  return {MakeBox(Vector3::Constant(big)), X_WG * Pose(Vector3(0, 0, -big))};
}

// Reference PD of probe against scene on tessellations; *tess_error gets the
// sum of both tessellation errors (the reference differs from the true PD
// by at most that).
inline ReferencePdResult ReferenceOnTessellations(const Geometry& P, const Isometry3& X_WP,
                                                  const Geometry& S, const Isometry3& X_WS,
                                                  double rel_chord_error, double* tess_error,
                                                  int num_directions = 400) {
  const double big = 20.0 * P.radius();
  const MeshStandIn p = StandIn(P, X_WP, rel_chord_error, big);
  const MeshStandIn s = StandIn(S, X_WS, rel_chord_error, big);
  *tess_error = pd::TessellationError(P, p.mesh) + (S.bounded() ? pd::TessellationError(S, s.mesh) : 0.0);
  ReferencePdOptions opt;
  opt.num_directions = num_directions;
  return ReferencePenetrationDepth(p.mesh, p.X_WM, true, s.mesh, s.X_WM, true, opt);
}

}  // namespace test
}  // namespace pd
