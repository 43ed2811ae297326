#pragma once
// One servo tick of 6-DOF haptic rendering, free of threads, clocks and
// transport so that it can be tested deterministically:
//   1. validate the newest pose (if any) and update the device state;
//   2. engage/watchdog scale;
//   3. penalty contact at the tool's current state;
//   4. implicit step of the tool under coupling + contact;
//   5. coupling reaction on the device at the new tool state;
//   6. conditioning (limits, rate, NaN guard).
// The tool appears at the device pose with the first valid pose, and again
// (force ramping up from zero) when a pose of another sender session arrives.
// Until then the output is zero with pose_seq -1. No allocation per tick once the PD
// solvers' scratch has grown.
#include <cstdint>

#include "haptics/build_scene.h"
#include "haptics/device_velocity.h"
#include "haptics/engage_envelope.h"
#include "haptics/penalty_wrench.h"
#include "haptics/pose_validation.h"
#include "haptics/scene_config.h"
#include "haptics/tool_dynamics.h"
#include "haptics/virtual_coupling.h"
#include "haptics/wrench_limiter.h"
#include "haptics/wrench_output.h"

namespace haptics {

struct RendererCounts {
  int64_t ticks = 0;
  int64_t poses_accepted = 0;
  PoseRejectionCounts poses_rejected;
  int64_t stale_ticks = 0;
  int64_t pd_invalid = 0;       // object queries whose PD was not verified
  int64_t pd_invalid_ticks = 0;
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
  const PenaltyContact& penalty() const { return penalty_; }
  const WrenchOutput& output() const { return output_; }
  RendererCounts counts() const;

 private:
  double dt_;
  PoseValidator validator_;
  DeviceVelocityEstimator velocity_;
  EngageEnvelope envelope_;
  PenaltyContact penalty_;
  ToolDynamics tool_;
  VirtualCoupling coupling_;
  WrenchLimiter limiter_;
  RigidState device_;
  const ContactSummary* contact_summary_;
  ContactSummary no_contact_;
  WrenchOutput output_;
  int64_t stale_ticks_ = 0;
  int64_t pd_invalid_ticks_ = 0;
  int64_t source_changes_ = 0;
};

}  // namespace haptics
