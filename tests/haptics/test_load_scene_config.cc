// Config errors name the file, the key and the allowed range; unknown keys
// are warned about; every shipped config loads and builds.
#include "haptics/scene/load_scene_config.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <regex>

#include "haptics/scene/build_scene.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

namespace fs = std::filesystem;

const char* kDevice = R"(
name: test_device
max_force: 12.0
max_torque: 0.2
max_force_rate: 2000.0
max_stiffness: 14500.0
workspace: {min: [-0.1, -0.1, -0.07], max: [0.1, 0.1, 0.07]}
)";

const char* kScene = R"(
name: test_scene
device: dev.yaml
tool:
  shape: {type: box, half_extents: [0.01, 0.01, 0.01]}
  mass: 0.02
  inertia: [1.0e-5, 1.0e-5, 1.0e-5]
objects:
  - name: table
    shape: {type: box, half_extents: [0.05, 0.05, 0.01]}
    pose: {position: [0, 0, -0.01], orientation: [1, 0, 0, 0]}
contact:
  stiffness: 3000.0
  damping: 5.0
coupling:
  translational: {stiffness: 1000.0, damping: 5.0}
  rotational: {stiffness: 0.5, damping: 0.003}
servo:
  rate_hz: 1000.0
)";

// A scene and device in a fresh directory; `edit` replaces text in the scene.
class ConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::WriteFile(dir_ / "dev.yaml", kDevice);
  }
  std::string Write(const std::string& scene, const std::string& from = "", const std::string& to = "") {
    const fs::path path = dir_ / "scene.yaml";
    test::WriteFile(path, test::Edited(scene, from, to));
    return path.string();
  }

  // Loads and builds; returns the ConfigError message ("" if it loaded).
  static std::string Error(const std::string& path) { return test::BuildError(path); }

  // The error must name the file, the key and contain each of `parts`.
  static void ExpectError(const std::string& path, const std::string& key,
                          std::initializer_list<std::string> parts) {
    test::ExpectConfigError(path, key, parts);
  }

  pd::test::ScopedTempDir tmp_{"haptics_test_config"};
  const fs::path dir_ = tmp_.path();
};

TEST_F(ConfigTest, ValidSceneLoadsWithDefaults) {
  const SceneConfig c = LoadSceneConfig(Write(kScene));
  EXPECT_EQ(c.name, "test_scene");
  EXPECT_EQ(c.device.name, "test_device");
  EXPECT_DOUBLE_EQ(c.device.max_torque_rate, 2000.0 * 0.2 / 12.0);  // derived default
  EXPECT_DOUBLE_EQ(c.contact.torque_scale, 1.0);
  EXPECT_DOUBLE_EQ(c.servo.watchdog_timeout_s, 0.05);
  EXPECT_EQ(c.lcm.pose_channel, "PROBE_POSE");
  EXPECT_EQ(c.lcm.wrench_channel, "HAPTIC_WRENCH");
  EXPECT_EQ(c.lcm.status_channel, "HAPTIC_STATUS");
  EXPECT_EQ(c.objects.size(), 1u);
  EXPECT_TRUE(c.objects[0].X_WS.translation().isApprox(Vector3(0, 0, -0.01)));
  EXPECT_TRUE(c.warnings.empty());
  const SceneModels m = BuildSceneModels(c);
  EXPECT_EQ(m.tool->kind(), pd::ShapeKind::kBox);  // the exact primitive
}

TEST_F(ConfigTest, MissingKeysAreNamed) {
  ExpectError(Write(kScene, "  stiffness: 3000.0\n", ""), "contact.stiffness",
              {"missing", "(0, 100000] N/m"});
  ExpectError(Write(kScene, "  mass: 0.02\n", ""), "tool.mass", {"missing", "(0, 10] kg"});
  ExpectError(Write(kScene, "servo:\n  rate_hz: 1000.0\n", ""), "servo", {"missing"});
  ExpectError(Write(kScene, "device: dev.yaml\n", ""), "device", {"missing"});
}

TEST_F(ConfigTest, WrongTypesAreNamed) {
  ExpectError(Write(kScene, "damping: 5.0\ncoupling", "damping: soft\ncoupling"), "contact.damping",
              {"must be a number in [0, 1000] N·s/m", "'soft'"});
  ExpectError(Write(kScene, "stiffness: 1000.0", "stiffness: [1, 2]"),
              "coupling.translational.stiffness", {"a list of 2"});
  ExpectError(Write(kScene, "half_extents: [0.01, 0.01, 0.01]", "half_extents: [0.01, 0.01]"),
              "tool.shape.half_extents", {"list of 3 numbers"});
  ExpectError(Write(kScene, "  rate_hz: 1000.0", "  rate_hz: {a: 1}"), "servo.rate_hz", {"a map"});
  ExpectError(Write(kScene, "type: box, half_extents: [0.05", "type: cube, half_extents: [0.05"),
              "objects[0].shape.type", {"must be one of", "spoon", "'cube'"});
}

TEST_F(ConfigTest, NonPositiveValuesAreRejectedWithTheRange) {
  ExpectError(Write(kScene, "stiffness: 3000.0", "stiffness: -5"), "contact.stiffness",
              {"(0, 100000] N/m", "'-5'"});
  ExpectError(Write(kScene, "stiffness: 3000.0", "stiffness: 0"), "contact.stiffness", {"'0'"});
  ExpectError(Write(kScene, "mass: 0.02", "mass: 0"), "tool.mass", {"(0, 10] kg"});
  ExpectError(Write(kScene, "mass: 0.02", "mass: -1"), "tool.mass", {"(0, 10] kg"});
  ExpectError(Write(kScene, "rate_hz: 1000.0", "rate_hz: 0"), "servo.rate_hz", {"[100, 10000] Hz"});
  ExpectError(Write(kScene, "rate_hz: 1000.0", "rate_hz: -1000"), "servo.rate_hz", {"[100, 10000] Hz"});
  ExpectError(Write(kScene, "rotational: {stiffness: 0.5", "rotational: {stiffness: .nan"),
              "coupling.rotational.stiffness", {"(0, 100] N·m/rad"});
  ExpectError(Write(kScene, "inertia: [1.0e-5, 1.0e-5, 1.0e-5]", "inertia: [1.0e-5, 0, 1.0e-5]"),
              "tool.inertia[1]", {"(0, 1] kg·m²"});
  ExpectError(Write(kScene, "inertia: [1.0e-5, 1.0e-5, 1.0e-5]", "inertia: [1.0e-5, 1.0e-5, 3.0e-5]"),
              "tool.inertia", {"triangle inequality"});
  ExpectError(Write(kScene, "  rate_hz: 1000.0", "  rate_hz: 1000.0\n  watchdog_timeout_ms: 1"),
              "servo.watchdog_timeout_ms", {"[2, 1000] ms"});
}

TEST_F(ConfigTest, LcmSectionAndTorqueModel) {
  const std::string lcm = "lcm:\n  url: memq://\n  pose_channel: POSES\n";
  SceneConfig c = LoadSceneConfig(Write(std::string(kScene) + lcm));
  EXPECT_EQ(c.lcm.url, "memq://");
  EXPECT_EQ(c.lcm.pose_channel, "POSES");
  EXPECT_EQ(c.lcm.wrench_channel, "HAPTIC_WRENCH");
  ExpectError(Write(std::string(kScene) + "lcm:\n  wrench_channel: PROBE_POSE\n"),
              "lcm.wrench_channel", {"must differ from lcm.pose_channel"});
  ExpectError(Write(std::string(kScene) + "lcm:\n  status_channel: " + std::string(64, 'X') + "\n"),
              "lcm.status_channel", {"at most 63 characters"});
  EXPECT_EQ(c.contact.torque_model, TorqueModel::kPressureCentre);
  c = LoadSceneConfig(Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  torque_model: region_points\ncoupling"));
  EXPECT_EQ(c.contact.torque_model, TorqueModel::kRegionPoints);
  ExpectError(Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  torque_model: magic\ncoupling"),
              "contact.torque_model", {"pressure_centre, region_points"});
}

TEST_F(ConfigTest, GeometryThreadHoldAgeingAndTickTrigger) {
  SceneConfig c = LoadSceneConfig(Write(kScene));
  EXPECT_EQ(c.contact.geometry_thread, GeometryThreadMode::kAuto);
  EXPECT_DOUBLE_EQ(c.contact.invalid_hold_s, 0.2);
  EXPECT_DOUBLE_EQ(c.contact.model_max_age_s, 0.25);
  EXPECT_DOUBLE_EQ(c.contact.geometry_budget_s, 0.0009);
  EXPECT_TRUE(c.servo.pose_triggered);
  c = LoadSceneConfig(Write(kScene, "  damping: 5.0\ncoupling",
                            "  damping: 5.0\n  geometry_thread: on\n  invalid_hold_ms: 50\n"
                            "  model_max_age_ms: 30\n  model_age_ramp_ms: 10\n  sync_budget: 0.5\ncoupling"));
  EXPECT_EQ(c.contact.geometry_thread, GeometryThreadMode::kOn);
  EXPECT_DOUBLE_EQ(c.contact.invalid_hold_s, 0.05);
  EXPECT_DOUBLE_EQ(c.contact.model_max_age_s, 0.03);
  EXPECT_DOUBLE_EQ(c.contact.model_age_ramp_s, 0.01);
  EXPECT_DOUBLE_EQ(c.contact.sync_budget, 0.5);
  c = LoadSceneConfig(Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  geometry_budget_ms: 5\ncoupling"));
  EXPECT_DOUBLE_EQ(c.contact.geometry_budget_s, 0.005);
  ExpectError(Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  geometry_budget_ms: 0\ncoupling"),
              "contact.geometry_budget_ms", {"ms"});
  c = LoadSceneConfig(Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  geometry_thread: off\ncoupling"));
  EXPECT_EQ(c.contact.geometry_thread, GeometryThreadMode::kOff);
  ExpectError(Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  geometry_thread: sometimes\ncoupling"),
              "contact.geometry_thread", {"auto, on, off"});
  ExpectError(Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  model_max_age_ms: 0\ncoupling"),
              "contact.model_max_age_ms", {"ms"});
  c = LoadSceneConfig(Write(kScene, "  rate_hz: 1000.0\n", "  rate_hz: 1000.0\n  tick_trigger: fixed_rate\n"));
  EXPECT_FALSE(c.servo.pose_triggered);
  ExpectError(Write(kScene, "  rate_hz: 1000.0\n", "  rate_hz: 1000.0\n  tick_trigger: sometimes\n"),
              "servo.tick_trigger", {"pose, fixed_rate"});
  EXPECT_TRUE(LoadSceneConfig(Write(kScene)).servo.io_on_servo_cpu);
  c = LoadSceneConfig(Write(kScene, "  rate_hz: 1000.0\n", "  rate_hz: 1000.0\n  io_on_servo_cpu: false\n"));
  EXPECT_FALSE(c.servo.io_on_servo_cpu);
  ExpectError(Write(kScene, "  rate_hz: 1000.0\n", "  rate_hz: 1000.0\n  io_on_servo_cpu: maybe\n"),
              "servo.io_on_servo_cpu", {"true, false"});
}

TEST_F(ConfigTest, CouplingAboveWhatTheDeviceRendersIsRejected) {
  ExpectError(Write(kScene, "stiffness: 1000.0", "stiffness: 20000.0"),
              "coupling.translational.stiffness", {"(0, 14500] N/m", "max_stiffness", "dev.yaml"});
}

TEST_F(ConfigTest, BadPosesAndShapesAreNamed) {
  ExpectError(Write(kScene, "orientation: [1, 0, 0, 0]", "orientation: [0.5, 0, 0, 0]"),
              "objects[0].pose.orientation", {"unit quaternion [w, x, y, z]"});
  ExpectError(Write(kScene, "orientation: [1, 0, 0, 0]", "orientation: [0, 0, 0, 0]"),
              "objects[0].pose.orientation", {"unit quaternion"});
  // Caught when the mesh is generated: minor radius >= major radius.
  ExpectError(Write(kScene, "shape: {type: box, half_extents: [0.05, 0.05, 0.01]}",
                    "shape: {type: torus, major_radius: 0.01, minor_radius: 0.02}"),
              "objects[0].shape", {"MakeTorus", "minor_radius < major_radius"});
}

TEST_F(ConfigTest, DeviceProfileErrorsNameTheDeviceFile) {
  std::string bad = kDevice;
  bad.replace(bad.find("max_force_rate: 2000.0"), 21, "max_force_rate: 0");
  test::WriteFile(dir_ / "dev.yaml", bad);
  const std::string message = Error(Write(kScene));
  EXPECT_NE(message.find((dir_ / "dev.yaml").string() + ": max_force_rate:"), std::string::npos) << message;
  EXPECT_NE(message.find("(0, 1e+06] N/s"), std::string::npos) << message;
  bad = kDevice;
  bad.replace(bad.find("max: [0.1, 0.1, 0.07]"), 21, "max: [0.1, -0.2, 0.07]");
  test::WriteFile(dir_ / "dev.yaml", bad);
  EXPECT_NE(Error(Write(kScene)).find("workspace.max[1]"), std::string::npos);
  fs::remove(dir_ / "dev.yaml");
  ExpectError(Write(kScene), "device", {"dev.yaml", "does not exist"});
}

TEST_F(ConfigTest, MissingMeshFileIsNamed) {
  const std::string path = Write(kScene, "shape: {type: box, half_extents: [0.05, 0.05, 0.01]}",
                                 "shape: {type: mesh, file: meshes/table.obj, scale: 0.001}");
  ExpectError(path, "objects[0].shape.file", {(dir_ / "meshes/table.obj").string(), "does not exist"});
}

TEST_F(ConfigTest, MeshFilesLoadRelativeToTheConfigFile) {
  fs::create_directories(dir_ / "meshes");
  // A 10 mm cube written in millimetres (quads, triangulated on load).
  test::WriteFile(dir_ / "meshes/cube.obj",
                  "v -5 -5 -5\nv 5 -5 -5\nv -5 5 -5\nv 5 5 -5\nv -5 -5 5\nv 5 -5 5\nv -5 5 5\nv 5 5 5\n"
                  "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
  const SceneConfig c = LoadSceneConfig(Write(
      kScene, "shape: {type: box, half_extents: [0.01, 0.01, 0.01]}",
      "shape: {type: mesh, file: meshes/cube.obj, scale: 0.001}"));
  const SceneModels m = BuildSceneModels(c);
  ASSERT_EQ(m.tool->kind(), pd::ShapeKind::kMesh);
  EXPECT_EQ(m.tool->model()->mesh().num_triangles(), 12);
  EXPECT_NEAR(m.tool->radius(), 0.005 * std::sqrt(3.0), 1e-9);
  // A broken mesh file is named too.
  test::WriteFile(dir_ / "meshes/broken.obj", "this is not an obj file\n");
  ExpectError(Write(kScene, "shape: {type: box, half_extents: [0.01, 0.01, 0.01]}",
                    "shape: {type: mesh, file: meshes/broken.obj}"),
              "tool.shape", {"broken.obj"});
}

TEST_F(ConfigTest, UnknownKeysAreWarnedNamingFileAndKey) {
  auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(64);
  auto previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", sink));
  const std::string path = Write(kScene, "  damping: 5.0\ncoupling", "  damping: 5.0\n  stifness: 3\ncoupling");
  const SceneConfig c = LoadSceneConfig(path);
  spdlog::set_default_logger(previous);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find(path + ": contact.stifness: unknown key"), std::string::npos)
      << c.warnings[0];
  bool logged = false;
  for (const std::string& line : sink->last_formatted())
    logged |= line.find("contact.stifness") != std::string::npos && line.find("warning") != std::string::npos;
  EXPECT_TRUE(logged) << "spdlog warn expected";
}

TEST_F(ConfigTest, YamlSyntaxErrorsNameTheLine) {
  const std::string message = Error(Write(kScene, "  mass: 0.02", "  mass: [0.02"));
  EXPECT_NE(message.find("YAML syntax error at line"), std::string::npos) << message;
  EXPECT_NE(message.find("scene.yaml"), std::string::npos) << message;
}

TEST(ShippedConfigs, EveryConfigLoadsAndBuilds) {
  int scenes = 0, devices = 0;
  for (const auto& entry : fs::directory_iterator(test::ConfigDir())) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const SceneConfig c = LoadSceneConfig(entry.path().string());
    EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
    const SceneModels m = BuildSceneModels(c);
    EXPECT_FALSE(m.objects.empty());
    auto triangles_of = [](const pd::Geometry& g) {
      return g.model() ? g.model()->mesh().num_triangles() : 0;  // primitives: none
    };
    int triangles = triangles_of(*m.tool);
    for (const SceneObject& o : m.objects) {
      if (o.geometry->model()) EXPECT_TRUE(o.geometry->model()->closed()) << o.name;
      triangles += triangles_of(*o.geometry);
    }
    // Modest where the tick waits for the geometry; the default scene
    // (knot_on_bunny, 82k triangles, a mesh tool) runs PolyDepth on the
    // geometry thread.
    if (c.contact.geometry_thread == GeometryThreadMode::kOff || !m.tool->model())
      EXPECT_LE(triangles, 5000);
    else
      EXPECT_LE(triangles, 200000);
    ++scenes;
  }
  for (const auto& entry : fs::directory_iterator(test::ConfigDir() + "/devices")) {
    if (entry.path().extension() != ".yaml") continue;
    std::vector<std::string> warnings;
    const DeviceConfig d = LoadDeviceConfig(entry.path().string(), &warnings);
    EXPECT_TRUE(warnings.empty()) << entry.path();
    EXPECT_GT(d.max_force, 0.0);
    ++devices;
  }
  EXPECT_GE(scenes, 3);
  EXPECT_GE(devices, 2);
}

TEST_F(ConfigTest, PhaseLockDefaultsOnAndIsValidated) {
  const SceneConfig c = LoadSceneConfig(Write(kScene));
  EXPECT_TRUE(c.servo.phase_lock);
  EXPECT_DOUBLE_EQ(c.servo.phase_lock_target_us, 150.0);
  const SceneConfig off = LoadSceneConfig(
      Write(kScene, "  rate_hz: 1000.0\n", "  rate_hz: 1000.0\n  phase_lock: false\n  phase_lock_target_us: 80\n"));
  EXPECT_FALSE(off.servo.phase_lock);
  EXPECT_DOUBLE_EQ(off.servo.phase_lock_target_us, 80.0);
  // More than half a period would let an on-time pose wait a whole one.
  ExpectError(Write(kScene, "  rate_hz: 1000.0\n", "  rate_hz: 1000.0\n  phase_lock_target_us: 700\n"),
              "servo.phase_lock_target_us", {"700"});
  ExpectError(Write(kScene, "  rate_hz: 1000.0\n", "  rate_hz: 1000.0\n  phase_lock: maybe\n"),
              "servo.phase_lock", {"maybe"});
}

}  // namespace
}  // namespace haptics
