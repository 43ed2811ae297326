#pragma once
// The penetration-depth dispatcher: one PairPdSolver per (probe, scene object)
// pair picks the cheapest exact method for the pair's kinds and owns that
// pair's warm-start state (like PolyDepthSolver: different pairs may be solved
// on different threads at once; Geometry objects are immutable and shared).
//
// Methods (ChoosePdMethod):
//  - kClosedForm: any bounded geometry against a half-space scene (general
//    meshes included: depth = max depth of the mesh's hull vertices below the
//    plane, translation along the plane normal; exact), sphere-sphere,
//    sphere-box, sphere-capsule, capsule-capsule (either order).
//  - kConvexGjkEpa: every other pair of convex kinds, by our own GJK + EPA in
//    double precision over support functions (pd_core/gjk_epa.h). Departure
//    from the "FCL with libccd": FCL 0.7's libccd EPA overestimates
//    PD by up to 40% and its GST_INDEP solver sometimes underestimates it, so
//    FCL is kept only as a cross-check in tests and a baseline in bench/.
//    Spheres and capsules run as their core (point, segment) plus margin.
//  - kPolyDepth: a general (non-convex) mesh against anything but a
//    half-space. A primitive on the other side is tessellated once at
//    construction (pd_core/geometry/tessellate_geometry.h), circumscribing it with a
//    chord error of at most kTessellationChordError (1%) of its radius (a
//    sphere: 1280 triangles), so a translation that frees the tessellation
//    frees the primitive; the depth is PolyDepth's for the tessellation and
//    may exceed the primitive's by up to that error.
//
// Result (same contract as PolyDepthSolver::Solve): translation_W moves the
// probe out (depth = |translation_W|, an upper bound on the true PD, backed
// off by options.separation_margin x size); normal_W its direction; regions
// carry the contact point on the probe (the probe's deepest point along
// -normal), the normal and the local depth; `valid` is a separation
// certificate (closed form and GJK/EPA: a separating plane at the answer).
// `iterations` counts GJK + EPA iterations. Touching (zero depth) counts as
// free for the closed forms and GJK/EPA.
#include <functional>
#include <memory>

#include "pd_core/geometry/geometry.h"
#include "pd_core/polydepth/penetration_result.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/geometry/pose.h"

namespace pd {

enum class PdMethod { kClosedForm, kConvexGjkEpa, kPolyDepth };
const char* PdMethodName(PdMethod method);

// The method PairPdSolver uses for this pair. Throws std::invalid_argument if
// the probe is a half-space (a probe must be bounded).
PdMethod ChoosePdMethod(const Geometry& probe, const Geometry& scene);

class PairPdSolver {
 public:
  // Chord error of primitive tessellations for PolyDepth, relative to radius.
  static constexpr double kTessellationChordError = 1e-2;

  // Throws std::invalid_argument for a null geometry or a half-space probe.
  PairPdSolver(std::shared_ptr<const Geometry> probe, std::shared_ptr<const Geometry> scene,
               PolyDepthOptions options = {});
  ~PairPdSolver();
  PairPdSolver(const PairPdSolver&) = delete;
  PairPdSolver& operator=(const PairPdSolver&) = delete;

  // PD of the probe at X_WP against the scene object at X_WS. With coherent =
  // true the previous answer of this pair warm-starts the search.
  PenetrationResult Solve(const Isometry3& X_WP, const Isometry3& X_WS, bool coherent = false);

  // PolyDepth's deferred work (PolyDepthOptions::defer_list_builds,
  // PolyDepthSolver::PrepareNext): true once none is left (at once for the
  // other methods, which defer nothing).
  bool PrepareNext(const std::function<bool()>& pause = {});

  // Forgets the previous answer (e.g. after a jump of the probe).
  void ResetWarmStart();

  PdMethod method() const { return method_; }
  const PolyDepthOptions& options() const { return options_; }
  const Geometry& probe() const { return *probe_; }
  const Geometry& scene() const { return *scene_; }
  // Queries where EPA hit its iteration cap and the answer came from the
  // best EPA bound refined by a directional sampling search (still verified).
  long epa_fallbacks() const { return epa_fallbacks_; }

 private:
  struct Impl;
  std::shared_ptr<const Geometry> probe_, scene_;
  PolyDepthOptions options_;
  PdMethod method_;
  long epa_fallbacks_ = 0;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pd
