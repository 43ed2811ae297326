#pragma once
// One servo tick of 6-DOF haptic rendering, free of threads, clocks and
// transport so that it can be tested deterministically:
//   1. validate the newest pose (if any) and update the device state;
//   2. engage/watchdog scale;
//   3. penalty contact at the tool's current state: the local contact model
//      (local_contact_model.h) of the newest geometry answer, queried in the
//      tick (synchronous) or on the geometry thread (geometry_thread.h), see
//      "Geometry" below;
//   4. implicit step of the tool under coupling + contact;
//   5. coupling reaction on the device at the new tool state;
//   6. conditioning (limits, rate, NaN guard).
// The tool appears at the device pose with the first valid pose, and again
// (force ramping up from zero) when a pose of another sender session arrives.
// Until then the output is zero with pose_seq -1. No allocation per tick once the PD
// solvers' scratch has grown.
//
// Geometry (contact.geometry_thread): the renderer itself never starts a
// thread. Unless someone drives geometry_worker() (GeometryThread, started by
// ServoLoop, or a test calling RunOnce) and says so with
// set_geometry_worker_running(true), every tick queries in line. With a
// worker: `on` posts the tool pose to it every tick and renders the newest
// answer's model (never waiting); `auto` queries in line while the query fits
// contact.sync_budget of the period and goes to the worker when one does not
// (or from the start when some pair is solved by PolyDepth), and comes back
// once the worker's answers have fitted the budget for a second and it is
// idle; `off` always queries in line.
#include <cstdint>

#include "haptics/scene/build_scene.h"
#include "haptics/tool/device_velocity.h"
#include "haptics/contact/contact_geometry.h"
#include "haptics/contact/engage_envelope.h"
#include "haptics/contact/geometry_thread.h"
#include "haptics/contact/local_contact_model.h"
#include "haptics/contact/penalty_wrench.h"
#include "haptics/io/pose_validation.h"
#include "haptics/scene/scene_config.h"
#include "haptics/tool/tool_dynamics.h"
#include "haptics/tool/virtual_coupling.h"
#include "haptics/tool/wrench_limiter.h"
#include "haptics/io/wrench_output.h"

namespace haptics {

struct RendererCounts {
  int64_t ticks = 0;
  int64_t poses_accepted = 0;
  PoseRejectionCounts poses_rejected;
  int64_t stale_ticks = 0;
  int64_t pd_invalid = 0;       // pair answers not verified (of the answers the tick took)
  int64_t pd_invalid_ticks = 0;  // ticks with a pair's newest answer not verified
  int64_t pd_held_ticks = 0;     // ... of which rendered the pair's last valid contact (hold)
  int64_t model_updates = 0;     // geometry answers taken (the PD update count)
  int64_t model_stale_ticks = 0; // ticks with the contact model past contact.model_max_age_ms
  int64_t model_outdated_answers = 0;  // geometry answers older than the model in use, dropped
  int64_t geometry_async_ticks = 0;  // ticks rendered from the geometry thread's answers
  int64_t geometry_switches = 0;     // auto: changes between in-tick and threaded geometry
  int64_t tool_nonfinite = 0;   // tool steps that went non-finite (tool stopped)
  LimiterCounts limiter;
  int64_t watchdog_trips = 0;
  int64_t source_changes = 0;   // valid poses of a new sender session: re-engaged from zero
};

class HapticRenderer {
 public:
  // pd_options: PolyDepth settings for every object (defaults are tuned).
  HapticRenderer(const SceneConfig& config, const SceneModels& models,
                 const pd::PolyDepthOptions& pd_options = {});

  // One tick at time t (s, the loop's clock; ticks are 1/rate apart). `pose`:
  // the newest sample received since the previous tick, or nullptr.
  const WrenchOutput& Tick(double t, const PoseSample* pose);

  double dt() const { return dt_; }
  bool engaged() const { return envelope_.engaged(); }
  const RigidState& tool() const { return tool_.state(); }
  const RigidState& device() const { return device_; }
  const ContactSummary& contact() const { return *contact_summary_; }
  const ToolDynamics& tool_dynamics() const { return tool_; }
  const VirtualCoupling& coupling() const { return coupling_; }
  // Geometry: see the header comment. geometry() must not be touched while
  // the worker runs (geometry_async()).
  const ContactGeometry& geometry() const { return geometry_; }
  GeometryWorker& geometry_worker() { return worker_; }
  // Whether contact.geometry_thread wants a worker driven (on, or auto).
  bool wants_geometry_thread() const;
  // Tell the renderer a worker runs (true) or stopped (false, before Tick
  // is called again; the renderer then queries in line).
  void set_geometry_worker_running(bool running);
  bool geometry_async() const { return async_; }
  // Ticks since the tool pose of the contact model in use (0: queried this
  // tick; -1: no model yet).
  int64_t model_age_ticks() const { return model_age_; }
  const LocalContactModel& local_contact() const { return local_; }
  // The last tick's geometry work, counted: the contact model terms it
  // evaluated when it rendered the geometry thread's answer (0 before the
  // tool engaged); -1 when it queried the geometry in line (PolyDepth's cost
  // is not a fixed amount per unit). The servo loop uses it to tell a tick
  // that overran its work from one charged time by the platform (miss_cause.h).
  int64_t tick_work() const { return tick_work_; }
  const WrenchOutput& output() const { return output_; }
  RendererCounts counts() const;

 private:
  double dt_;
  PoseValidator validator_;
  DeviceVelocityEstimator velocity_;
  EngageEnvelope envelope_;
  ContactGeometry geometry_;
  LocalContactModel local_;
  GeometryWorker worker_;
  ContactSnapshot sync_answer_;
  GeometryThreadMode mode_;
  double sync_budget_us_;
  bool worker_running_ = false;
  bool async_ = false;
  int64_t fit_answers_ = 0;   // consecutive worker answers within the budget
  int64_t model_age_ = -1;
  int64_t tick_work_ = 0;
  int64_t async_ticks_ = 0, switches_ = 0;
  ToolDynamics tool_;
  VirtualCoupling coupling_;
  WrenchLimiter limiter_;
  RigidState device_;
  const ContactSummary* contact_summary_;
  // The contact model of the tool at this tick (in line or from the worker).
  const ContactSummary& ContactAt(const RigidState& tool, int32_t* flags);
  ContactSummary no_contact_;
  WrenchOutput output_;
  int64_t stale_ticks_ = 0;
  int64_t pd_invalid_ticks_ = 0;
  int64_t source_changes_ = 0;
};

}  // namespace haptics
