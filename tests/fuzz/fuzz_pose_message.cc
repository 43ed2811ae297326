// libFuzzer target: arbitrary bytes as a burst of raw pose-channel messages
// through the server's real handling: haptics::PoseReceiver::OnMessage (the
// probe_pose_t decode the receive thread runs), the newest pose handed over
// through the LatestValue, and a fresh haptics::HapticRenderer on the shipped
// box_on_box scene ticking on it (validation, engage, PD contact, dynamics,
// limits), as the servo loop does. The receiver's pose source lock is on
// (any sender may be the first; others are rejected while it is alive).
//
// Input: repeated [n][n bytes] chunks, each one message; after each, one tick
// (and a stale tick when n is odd). Contract: never a crash; every wrench
// finite and within the device's force and torque limits; every undecodable
// message counted as malformed, every decoded one as received or as rejected
// by the source lock (other sender, no identity, other version).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "fuzz_temp_file.h"
#include "haptics/scene/build_scene.h"
#include "haptics/haptic_renderer.h"
#include "haptics/io/lcm_io.h"
#include "haptics/scene/load_scene_config.h"

namespace {

struct Scene {
  haptics::SceneConfig config;
  haptics::SceneModels models;
};

const Scene& TheScene() {
  static const Scene* scene = [] {
    auto* s = new Scene;
    s->config = haptics::LoadSceneConfig(PD_FUZZ_CONFIG_DIR "/box_on_box.yaml");
    s->config.servo.soft_engage_s = 0.0;  // full force from the first pose
    s->models = haptics::BuildSceneModels(s->config);
    return s;
  }();
  return *scene;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static lcm::LCM lcm("memq://");  // in-process; OnMessage is called directly
  const Scene& scene = TheScene();
  haptics::LatestValue<haptics::PoseSample> poses;
  haptics::PoseReceiver receiver(&lcm, "PROBE_POSE", &poses,
                                 haptics::MakePoseSourceOptions(scene.config, haptics::PoseSourcePin{}));
  haptics::HapticRenderer renderer(scene.config, scene.models);
  const double max_force = scene.config.device.max_force * (1.0 + 1e-9);
  const double max_torque = scene.config.device.max_torque * (1.0 + 1e-9);
  auto check = [&](const haptics::WrenchOutput& out) {
    if (!out.wrench.AllFinite()) pd_fuzz::Violation("non-finite wrench");
    if (out.wrench.f_W.norm() > max_force) pd_fuzz::Violation("force over the device limit");
    if (out.wrench.tau_W.norm() > max_torque) pd_fuzz::Violation("torque over the device limit");
    if (!std::isfinite(out.penetration_depth)) pd_fuzz::Violation("non-finite depth");
  };

  int64_t messages = 0;
  double t = 0.0;
  size_t i = 0;
  while (i < size) {
    const size_t n = std::min<size_t>(data[i], size - i - 1);
    receiver.OnMessage(n > 0 ? data + i + 1 : nullptr, static_cast<int>(n));
    ++messages;
    i += 1 + n;
    check(renderer.Tick(t, poses.TakeNewest()));
    t += renderer.dt();
    if (n % 2 == 1) {
      check(renderer.Tick(t, nullptr));
      t += renderer.dt();
    }
  }
  const haptics::ReceiverCounts counts = receiver.counts();
  if (counts.received + counts.malformed + counts.rejected_total() != messages)
    pd_fuzz::Violation("received + malformed + rejected != messages handled");
  return 0;
}
