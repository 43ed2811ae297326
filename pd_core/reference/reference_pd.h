#pragma once
// A slow, independent reference for translational penetration depth (PD), used
// to check the fast PolyDepth solver in tests and benchmarks. It shares no code
// with the fast path (no BVH, CCD or PolyDepth files): brute force with simple
// sort-and-sweep broad phases.
//
// Definition. The probe P (at X_WP) and scene object S (at X_WS) collide when a
// triangle of P intersects a triangle of S (closed triangles), or, if S is
// closed, a point of P lies inside S, or, if P is closed, a point of S lies
// inside P. PD(P, S) = min |t| over world translations t (metres) that leave P
// moved by t collision-free. Escapes into free slits thinner than
// slit_tol * size do not count, where size is the sum of the radii of the
// meshes' bounding spheres (centred at their bounding-box centres).
//
// Method. For a unit direction u the set of s with P moved by s*u touching S is
// the union over triangle pairs of closed intervals, each computed exactly from
// feature events; containment between the intervals is decided by ray parity.
// The exit distance along u is the start of the first free gap that is not a
// slit. A gap's thickness is its length along u times the larger |u·n| of the
// contact normals n at its two ends (exact for a slit between parallel walls,
// crossed at any angle; 1 is used where n is undefined). PD is the
// minimum of that over a Fibonacci sphere of directions, refined from the best
// few by jumping to the contact normal at the exit (the optimum for a single
// planar contact) and a pattern search with a shrinking step; the contact
// planes its exits report form a local model whose shortest point is tried
// when no pattern move gains (an optimum where two or three contacts meet,
// on a crease or corner of the C-obstacle, which the pattern's fixed axes
// only zig-zag toward). The result is
// an upper bound on the true PD: exact to rounding for convex polytopes, and
// for non-convex pairs it converges as directions and refinement starts grow.
// Cost: one direction is a few ms for 1k x 1k triangles.
#include <vector>

#include "pd_core/mesh/mesh.h"
#include "pd_core/geometry/pose.h"

namespace pd {

struct ReferencePdOptions {
  int num_directions = 2000;  // Fibonacci sphere of directions
  int refine_iterations = 60; // directional evaluations per refinement start
  int num_refine_starts = 4;  // best distinct directions that are refined
  double slit_tol = 1e-6;     // relative to size (sum of bounding radii)
  // Evaluated in addition to the sphere (world, need not be unit; zero vectors
  // are ignored), e.g. known face normals. Never the answer of a solver under
  // test: a reference seeded with it measures "close to what we found", not
  // "close to the true PD".
  std::vector<Vector3> extra_directions_W;
};

struct ReferencePdResult {
  bool in_collision = false;                // P at X_WP collides with S
  double depth = 0.0;                       // |translation_W| (m)
  Vector3 translation_W = Vector3::Zero();  // move P by this to separate (m)
  Vector3 direction_W = Vector3::Zero();    // unit, zero when not colliding
  int directions_evaluated = 0;             // directional exits computed
};

// Exact first-exit distance (m) of P moved along the unit world direction u_W:
// the smallest s >= 0 such that P moved by s*u_W is collision-free, ignoring
// free gaps thinner than slit_tol_abs (m). 0 if P does not collide.
double DirectionalPenetration(const TriangleMesh& probe, const Isometry3& X_WP,
                              bool probe_closed, const TriangleMesh& scene,
                              const Isometry3& X_WS, bool scene_closed,
                              const Vector3& u_W, double slit_tol_abs);

// Reference PD: minimum directional exit over the directions of `options`.
ReferencePdResult ReferencePenetrationDepth(const TriangleMesh& probe,
                                            const Isometry3& X_WP, bool probe_closed,
                                            const TriangleMesh& scene,
                                            const Isometry3& X_WS, bool scene_closed,
                                            const ReferencePdOptions& options = {});

// Independent boolean collision test of P moved by t_W (m, world) against S:
// sort-and-sweep over triangle boxes, orientation-predicate triangle tests
// and ray-parity containment. Degenerate (zero-area) triangles only count
// through their edges against non-degenerate triangles.
bool ReferenceInCollision(const TriangleMesh& probe, const Isometry3& X_WP,
                          bool probe_closed, const TriangleMesh& scene,
                          const Isometry3& X_WS, bool scene_closed,
                          const Vector3& t_W = Vector3::Zero());

}  // namespace pd
