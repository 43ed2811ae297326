// session_viewer: turns a scene file and a recorded session (probe_replay's
// result CSV, or an LCM log of probe poses and wrenches) into one
// self-contained HTML page: open it in any browser, no network needed.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>

#include "haptics/scene/build_scene.h"
#include "haptics/scene/load_scene_config.h"
#include "probes/transport/channels.h"
#include "probes/trajectory/input_error.h"
#include "probes/viewer/read_session.h"
#include "probes/viewer/rerender_session.h"
#include "probes/viewer/session_page.h"

namespace {

constexpr const char* kFooter = R"(
The page shows the scene meshes, the device pose (green ghost of the tool)
and the simulated tool (orange) over time on a slider with play/pause, the
recorded force (red) and torque (purple) on the device as arrows, and the
contact points (yellow) with their normals. The simulated tool pose and the
contacts are not sent over LCM: they are recomputed here by the server's own
renderer from the recorded device poses, and the recomputed force is compared
with the recorded one (printed, and shown on the page).

Exit codes: 0 page written; 1 bad input (scene, session, three.js missing);
2 the page could not be written.)";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"session_viewer: a browser page of a recorded haptic session"};
  app.footer(kFooter);
  std::string scene_path, session_path, out_path, cache_dir;
  std::string pose_channel = probes::kDefaultPoseChannel;
  std::string wrench_channel = probes::kDefaultWrenchChannel;
  probes::PageOptions page;
  app.add_option("--scene", scene_path, "scene YAML the session ran on (config/*.yaml)")->required();
  app.add_option("--session", session_path, "probe_replay result CSV or LCM log")->required();
  app.add_option("--out", out_path, "HTML page to write")->required();
  app.add_option("--pose-channel", pose_channel, "LCM log: channel of probe_pose_t")->capture_default_str();
  app.add_option("--wrench-channel", wrench_channel, "LCM log: channel of wrench_t")->capture_default_str();
  app.add_option("--three-dir", page.three_dir, "where three.min.js is (Debian libjs-three)")
      ->capture_default_str();
  app.add_option("--max-frames", page.max_frames,
                 "keep at most this many frames in the page (every k-th pose); 0: all")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--cache-dir", cache_dir, "mesh precomputation cache (as haptic_server)");
  CLI11_PARSE(app, argc, argv);

  haptics::SceneConfig config;
  haptics::SceneModels models;
  probes::Session session;
  try {
    config = haptics::LoadSceneConfig(scene_path);
    models = haptics::BuildSceneModels(config, cache_dir);
    session = probes::ReadSession(session_path, pose_channel, wrench_channel);
  } catch (const std::exception& e) {
    std::cerr << "session_viewer: " << e.what() << "\n";
    return 1;
  }
  const probes::RerenderedSession rerendered = probes::RerenderSession(config, models, session);
  std::ofstream out(out_path);
  if (!out) {
    std::cerr << "session_viewer: " << out_path << ": cannot open for writing\n";
    return 2;
  }
  try {
    probes::WriteSessionPage(out, config, models, session, rerendered, page);
  } catch (const std::exception& e) {
    std::cerr << "session_viewer: " << e.what() << "\n";
    return 1;
  }
  if (!out.flush()) {
    std::cerr << "session_viewer: " << out_path << ": write failed\n";
    return 2;
  }
  int64_t answered = 0;
  for (const probes::SessionFrame& f : session.frames) answered += f.answered ? 1 : 0;
  const probes::RerenderAgreement& a = rerendered.agreement;
  std::printf("session_viewer: %s (%zu poses, %lld answered) on scene '%s'\n", session_path.c_str(),
              session.frames.size(), static_cast<long long>(answered), config.name.c_str());
  std::printf("session_viewer: recomputed vs recorded force: median %.4f N, p99 %.4f N, max %.4f N "
              "(largest recorded force %.3f N)\n",
              a.median_force_diff, a.p99_force_diff, a.max_force_diff, a.max_recorded_force);
  std::printf("session_viewer: wrote %s\n", out_path.c_str());
  return 0;
}
