#pragma once
// Helpers shared by the haptics tests: a programmatic box-on-box scene (no
// YAML), pose samples, and file helpers.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include <initializer_list>

#include "haptics/scene/build_scene.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics/io/pose_sample.h"
#include "haptics/scene/scene_config.h"
#include "tests/scoped_temp_dir.h"

namespace haptics::test {

inline std::string ConfigDir() { return HAPTICS_CONFIG_DIR; }
// The loop benchmark's scenes, and the meshes they name (scripts/fetch_meshes.sh).
inline std::string BenchSceneDir() { return ConfigDir() + "/../bench/scenes"; }
inline std::string MeshDir() { return ConfigDir() + "/../build/meshes"; }

// A 2 cm box tool over a 10 x 10 x 2 cm table whose top face is z = 0.
inline SceneConfig BoxOnBoxConfig() {
  SceneConfig c;
  c.file = "box_on_box_test";
  c.name = "box_on_box_test";
  c.tool.shape = {"tool.shape", BoxShape{Vector3(0.01, 0.01, 0.01)}};
  c.tool.mass = 0.02;
  c.tool.I_T = 1e-5 * Matrix3::Identity();
  ObjectConfig table;
  table.name = "table";
  table.shape = {"objects[0].shape", BoxShape{Vector3(0.05, 0.05, 0.01)}};
  table.X_WS.translation() = Vector3(0, 0, -0.01);
  c.objects.push_back(table);
  c.contact = {3000.0, 5.0, 1.0, 0.005};
  c.coupling.k_translational = 1000.0;
  c.coupling.b_translational = 5.0;
  c.coupling.k_rotational = 0.5;
  c.coupling.b_rotational = 0.003;
  c.device.file = "test_device";
  c.device.name = "test_device";
  c.device.max_force = 12.0;
  c.device.max_torque = 0.2;
  c.device.max_force_rate = 2000.0;
  c.device.max_torque_rate = 33.0;
  c.device.max_stiffness = 14500.0;
  c.device.workspace_min = Vector3(-0.1, -0.1, -0.07);
  c.device.workspace_max = Vector3(0.1, 0.1, 0.07);
  c.servo.rate_hz = 1000.0;
  c.servo.watchdog_timeout_s = 0.05;
  c.servo.watchdog_ramp_s = 0.05;
  c.servo.soft_engage_s = 0.0;
  return c;
}

inline PoseSample MakePose(int64_t seq, const Vector3& p_WD,
                           const Quaternion& q_WD = Quaternion::Identity()) {
  PoseSample s;
  s.seq = seq;
  s.utime = 1000 * seq;  // 1 kHz sender clock
  s.p_WD = p_WD;
  s.q_WD = q_WD;
  return s;
}

inline void WriteFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

// `text` with its first `from` replaced by `to` (unchanged for an empty
// `from`); a `from` not in the text is a test bug and fails the test.
inline std::string Edited(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the text";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Loads and builds a scene file; the ConfigError message, "" if it built.
inline std::string BuildError(const std::string& path) {
  try {
    BuildSceneModels(LoadSceneConfig(path));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// The scene at `path` must fail with "<path>: <key>: ..." containing `parts`.
inline void ExpectConfigError(const std::string& path, const std::string& key,
                              std::initializer_list<std::string> parts) {
  const std::string message = BuildError(path);
  ASSERT_FALSE(message.empty()) << "expected an error for " << key;
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find(key + ":"), std::string::npos) << message;
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

// A tool state at rest at p_WT, turned by R_WT.
inline RigidState ToolAt(const Vector3& p_WT, const Matrix3& R_WT = Matrix3::Identity()) {
  RigidState s;
  s.X_W.translation() = p_WT;
  s.X_W.linear() = R_WT;
  return s;
}

}  // namespace haptics::test
