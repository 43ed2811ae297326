// The scene file's per-mesh `max_triangles` reaches pd::LoadMesh: a mesh
// over it is refused naming the config file, the shape's key and the limit;
// a bad value is a ConfigError naming the key and the range.
#include <gtest/gtest.h>

#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "haptics/scene/build_scene.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

namespace fs = std::filesystem;

// config/box_on_box.yaml with its table replaced by `table_shape`, written
// into a fresh directory next to a 12-triangle cube.obj and config/devices.
std::string SceneWithTable(const std::string& table_shape) {
  // One directory per scene (the error messages name its path); all removed
  // at exit.
  static std::deque<pd::test::ScopedTempDir> dirs;
  const fs::path dir = dirs.emplace_back("haptics_test_mesh_limit").path();
  fs::create_directory_symlink(test::ConfigDir() + "/devices", dir / "devices");
  test::WriteFile(dir / "cube.obj",
                  "v -5 -5 -5\nv 5 -5 -5\nv -5 5 -5\nv 5 5 -5\nv -5 -5 5\nv 5 -5 5\nv -5 5 5\nv 5 5 5\n"
                  "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
  std::ifstream in(test::ConfigDir() + "/box_on_box.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string table = "shape: {type: box, half_extents: [0.05, 0.05, 0.01]}";
  const size_t at = yaml.find(table);
  EXPECT_NE(at, std::string::npos) << "config/box_on_box.yaml changed: update this test";
  if (at != std::string::npos) yaml.replace(at, table.size(), "shape: " + table_shape);
  test::WriteFile(dir / "scene.yaml", yaml);
  return (dir / "scene.yaml").string();
}

TEST(MeshLimitConfig, MaxTrianglesIsHonouredAndNamed) {
  // 12 triangles: loads at 12, refused at 11.
  const SceneConfig ok =
      LoadSceneConfig(SceneWithTable("{type: mesh, file: cube.obj, scale: 0.001, max_triangles: 12}"));
  EXPECT_NO_THROW(BuildSceneModels(ok));
  const std::string path =
      SceneWithTable("{type: mesh, file: cube.obj, scale: 0.001, max_triangles: 11}");
  const SceneConfig over = LoadSceneConfig(path);
  try {
    BuildSceneModels(over);
    ADD_FAILURE() << "a 12-triangle mesh loaded with max_triangles: 11";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path, 0), 0u) << what;
    EXPECT_NE(what.find("objects[0].shape"), std::string::npos) << what;
    EXPECT_NE(what.find("max_triangles = 11"), std::string::npos) << what;
  }
  for (const std::string bad : {"0", "-5", "many", "1.5e9"}) {
    const std::string p = SceneWithTable("{type: mesh, file: cube.obj, max_triangles: " + bad + "}");
    try {
      LoadSceneConfig(p);
      ADD_FAILURE() << "max_triangles: " << bad << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("objects[0].shape.max_triangles"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace haptics
