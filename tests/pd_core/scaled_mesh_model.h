#pragma once
// A real mesh from the test mesh directory (scripts/fetch_meshes.sh), scaled
// about its file origin, built into a collision model: the bench's haptic
// pairs are these meshes at the scales bench_pd gives them.
#include <memory>
#include <string>
#include <utility>

#include "pd_core/mesh/collision_model.h"
#include "pd_core/mesh/load_mesh.h"

namespace pd {
namespace test {

inline std::shared_ptr<const CollisionModel> LoadScaled(const std::string& file, double scale) {
  TriangleMesh mesh = LoadMesh(std::string(PD_TEST_MESH_DIR) + "/" + file).mesh;
  for (Vector3& v : mesh.vertices) v *= scale;
  return CollisionModel::Build(std::move(mesh));
}

}  // namespace test
}  // namespace pd
