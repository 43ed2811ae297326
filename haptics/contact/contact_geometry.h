#pragma once
// The geometry side of penalty contact: at one tool pose, which objects the
// tool can reach (broad_phase.h), the PD of each with its own warm-started
// pd::PairPdSolver (closed form, GJK/EPA or PolyDepth), and from each answer
// the pair's local contact model (pair_contact_model.h): contact planes, local
// depths and the points where the forces act (pressure points: tool surface
// points inside the object, penalty_wrench.h). This is the expensive part of
// contact; it runs in the servo tick (synchronous) or on the geometry thread
// (geometry_thread.h). Velocity-dependent terms (damping) are left to the
// model's evaluation at the tool's current state.
//
// Culled objects cost nothing; an object leaving reach has its warm start
// dropped. A pair keeps its warm start over a jump of the tool (an answer
// that took long): it keeps the side of the contact, and PolyDepth's warm
// query after a jump costs about what a cold one does. Allocation-free once
// the solvers' scratch has grown. Not thread-safe: one thread queries at a
// time.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "haptics/contact/broad_phase.h"
#include "haptics/scene/build_scene.h"
#include "haptics/contact/pair_contact_model.h"
#include "haptics/scene/scene_config.h"
#include "haptics/scene/scene_object.h"
#include "haptics/tool/spatial.h"
#include "pd_core/pair_pd_solver.h"
#include "pd_core/polydepth/penetration_result.h"

namespace haptics {

// One query's answer for all objects in reach.
struct ContactSnapshot {
  int64_t request_tick = -1;                 // servo tick whose tool pose was queried
  Isometry3 X_WT0 = Isometry3::Identity();   // that pose
  int num_candidates = 0;                    // objects the broad phase kept
  int num_culled = 0;
  double query_us = 0.0;                     // wall time of the query (us)
  int num_pairs = 0;                         // used entries of `pairs`: one per candidate
  std::vector<PairContactModel> pairs;       // sized to the object count by Reserve()

  // Sizes `pairs` for `num_objects` (allocates; before any hot loop).
  void Reserve(int num_objects) { pairs.resize(static_cast<size_t>(num_objects)); }
};

class ContactGeometry {
 public:
  // The tool geometry in its frame G, placed in the tool frame T by X_TG.
  ContactGeometry(std::shared_ptr<const pd::Geometry> tool, const Isometry3& X_TG,
                  std::vector<SceneObject> objects, const ContactConfig& params,
                  pd::PolyDepthOptions options = {});

  // Broad phase over the tool's motion since the previous query, PD of every
  // candidate, their models into *out (Reserve()d for num_objects()).
  void Query(const Isometry3& X_WT, int64_t request_tick, ContactSnapshot* out);

  // The work the last queries deferred (PolyDepthOptions::defer_list_builds:
  // candidate-list rebuilds after their answers) for the pairs in reach,
  // until done (true) or pause() says stop (asked every few dozen box tests;
  // the next call goes on).
  bool PrepareNext(const std::function<bool()>& pause = {});

  // Forget warm starts and the previous pose (after the tool jumped).
  void ResetWarmStarts();

  int num_objects() const { return static_cast<int>(objects_.size()); }
  const SceneObject& object(int i) const { return objects_[i]; }
  const pd::PairPdSolver& solver(int i) const { return *solvers_[i]; }
  const BroadPhase& broad_phase() const { return broad_phase_; }
  // The last PD answer for object i (in_collision false if it was culled).
  const pd::PenetrationResult& last_result(int i) const { return results_[i]; }
  // Whether any pair is solved by PolyDepth (costs up to milliseconds).
  bool any_polydepth() const;
  int64_t query_count() const { return query_count_; }   // PD queries (object x call)
  int64_t invalid_count() const { return invalid_count_; }  // of those, not verified
  const ContactConfig& params() const { return params_; }

 private:
  void BuildModel(const pd::PenetrationResult& r, const SceneObject& object, const Isometry3& X_WT,
                  PairContactModel* m);
  // Tool pressure points inside `object` and below some region's plane, into inside_.
  void FindPressurePoints(const pd::PenetrationResult& r, const SceneObject& object);

  std::shared_ptr<const pd::Geometry> tool_;
  Isometry3 X_TG_;
  std::vector<SceneObject> objects_;
  ContactConfig params_;
  BroadPhase broad_phase_;
  std::vector<std::unique_ptr<pd::PairPdSolver>> solvers_;
  std::vector<pd::PenetrationResult> results_;
  // Broad-phase state.
  bool have_previous_ = false;
  WorldBox previous_box_W_;            // tool box at the previous call
  std::vector<int> candidates_now_;    // this call's candidates
  std::vector<int> candidates_prev_;   // the previous call's
  std::vector<int64_t> candidate_call_;  // per object: last call it was a candidate
  int64_t call_ = 0;
  // Scratch, sized at construction.
  Isometry3 X_WG_ = Isometry3::Identity();          // tool geometry pose this call
  std::vector<Vector3> p_WV_;                       // tool pressure points in W (those below a plane)
  std::vector<std::pair<double, int>> depth_points_;  // (depth below a plane, point)
  std::vector<int> inside_;                         // points inside the object
  double same_point_tol2_ = 0.0;  // (m²) a region point this close to a pressure point is it
  int64_t query_count_ = 0;
  int64_t invalid_count_ = 0;
};

}  // namespace haptics
