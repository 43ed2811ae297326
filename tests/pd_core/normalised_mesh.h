#pragma once
// Real test meshes (libcgal-demo's, scripts/fetch_meshes.sh) at the
// benchmark's scale, so a pose taken from a bench_pd case reproduces it.
#include <algorithm>
#include <string>

#include "pd_core/mesh/load_mesh.h"
#include "pd_core/mesh/mesh.h"

namespace pd::test {

// The mesh PD_TEST_MESH_DIR/name scaled to a 0.1 m bounding sphere about its
// box centre (as the benchmark does), times `extra_scale`.
inline TriangleMesh LoadNormalised(const std::string& name, double extra_scale = 1.0) {
  TriangleMesh mesh = LoadMesh(std::string(PD_TEST_MESH_DIR) + "/" + name).mesh;
  const MeshBounds b = ComputeBounds(mesh);
  double r = 0.0;
  for (const Vector3& v : mesh.vertices) r = std::max(r, (v - b.center()).norm());
  for (Vector3& v : mesh.vertices) v *= extra_scale * 0.1 / r;
  return mesh;
}

}  // namespace pd::test
