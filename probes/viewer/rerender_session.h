#pragma once
// The simulated tool and its contacts for a recorded session. Neither is on
// the wire (wrench_t carries the device wrench, depth and contact count
// only), so they are recomputed offline: the server's own renderer
// (haptics::HapticRenderer: PolyDepth contact, tool dynamics, coupling,
// limits) is run on the recorded device poses at the server's rate, one tick
// per pose in its send-time slot. Its wrench is compared with the recorded
// one, so the page can say how closely the recomputation matches the run.
#include <cstdint>
#include <vector>

#include "haptics/scene/build_scene.h"
#include "haptics/scene/scene_config.h"
#include "probes/viewer/session_data.h"

namespace probes {

struct ContactPoint {
  pd::Vector3 p_W = pd::Vector3::Zero();  // contact point on the tool (m)
  pd::Vector3 n_W = pd::Vector3::UnitZ(); // unit normal, out of the object
  double depth = 0.0;                     // local depth (m)
};

struct RenderedFrame {
  pd::Isometry3 X_WT = pd::Isometry3::Identity();  // simulated tool pose
  pd::Vector3 f_W = pd::Vector3::Zero();           // recomputed device force (N)
  std::vector<ContactPoint> contacts;
};

struct RerenderAgreement {
  int64_t compared = 0;          // answered frames compared
  double max_recorded_force = 0; // N
  double median_force_diff = 0;  // |f_recomputed - f_recorded| (N)
  double p99_force_diff = 0;
  double max_force_diff = 0;
};

struct RerenderedSession {
  std::vector<RenderedFrame> frames;  // one per session frame
  RerenderAgreement agreement;
};

RerenderedSession RerenderSession(const haptics::SceneConfig& config,
                                  const haptics::SceneModels& models, const Session& session);

}  // namespace probes
