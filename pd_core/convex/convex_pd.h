#pragma once
// Penetration depth of two convex geometries by GJK + EPA over support
// functions (our own, double precision; pd_core/convex/gjk.h, pd_core/convex/epa.h).
// Departure from the "FCL with libccd": FCL 0.7's libccd EPA
// overestimates PD by up to 40% and its GST_INDEP solver sometimes
// underestimates it (measured), so FCL serves only as a cross-check in tests
// and a baseline in bench/.
//
// Spheres and capsules run as their cores (point, segment) with the radii as
// a margin m: GJK on the cores; if they are apart by δ < m the PD is m - δ
// along the closest-point direction, if they overlap EPA gives the cores' PD
// and the margin is added. Either way the reported depth along the chosen
// unit normal n is the support value h_S(n) + h_P(-n) of the full shapes, so
// moving the probe by depth * n provably separates them (an upper bound,
// within tol of the true PD when EPA converged). If EPA hits its iteration
// cap, a directional sampling search around the best EPA normal refines the
// bound (converged = false).
#include "pd_core/convex/epa.h"
#include "pd_core/geometry/geometry.h"
#include "pd_core/convex/pair_pd_answer.h"

namespace pd {

struct ConvexPdOptions {
  double rel_tol = 1e-9;        // EPA/GJK tolerance, fraction of the pair's size
  int max_gjk_iterations = 64;
  int max_epa_iterations = 128;
  int num_fallback_directions = 64;  // sampling search when EPA fails
};

// Probe P at X_WP, scene S at X_WS, both convex and bounded. guess_W: a
// direction to start GJK from (e.g. the previous normal; zero: centre
// difference). scratch is reused across calls.
PairPdAnswer ConvexPenetrationDepth(const Geometry& probe, const Isometry3& X_WP,
                                    const Geometry& scene, const Isometry3& X_WS,
                                    const ConvexPdOptions& options, const Vector3& guess_W,
                                    EpaScratch* scratch);

// Signed distance (m) between two convex bounded geometries by GJK, for
// verifying answers: > 0 apart, ~0 touching (within 1e-13 x size), < 0 when
// they overlap (then only -max(margins, tol): not the depth).
double ConvexDistance(const Geometry& a, const Isometry3& X_WA, const Geometry& b,
                      const Isometry3& X_WB);

}  // namespace pd
