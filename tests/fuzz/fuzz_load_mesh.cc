// libFuzzer target: arbitrary bytes as a mesh file through pd::LoadMesh's
// real path (a file on disk; assimp picks its reader by the extension). The
// first byte chooses the extension (.off, .obj, .stl, .ply), the rest is the
// file. Contract: a LoadedMesh with finite vertices within the coordinate
// limit and triangle indices in range, or a pd::MeshLoadError whose message
// names the file. Anything else (another exception, a crash, a sanitizer
// report, a hang) is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_temp_file.h"
#include "pd_core/mesh/load_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {".off", ".obj", ".stl", ".ply"};
  const std::string path =
      pd_fuzz::WriteTempFile(std::string("mesh") + kExtensions[data[0] % 4], data + 1, size - 1);
  pd::MeshLoadOptions options;  // the defaults the server uses
  try {
    const pd::LoadedMesh loaded = pd::LoadMesh(path, options);
    const pd::TriangleMesh& mesh = loaded.mesh;
    if (mesh.num_triangles() < 1) pd_fuzz::Violation("loaded a mesh with no triangles");
    if (mesh.num_triangles() > options.max_triangles) pd_fuzz::Violation("over max_triangles");
    for (const pd::Vector3& p : mesh.vertices) {
      if (!p.allFinite()) pd_fuzz::Violation("non-finite vertex loaded");
      if (p.cwiseAbs().maxCoeff() > options.max_abs_coordinate)
        pd_fuzz::Violation("vertex beyond max_abs_coordinate loaded");
    }
    for (const Eigen::Vector3i& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        if (t[k] < 0 || t[k] >= mesh.num_vertices()) pd_fuzz::Violation("index out of range");
      }
    }
  } catch (const pd::MeshLoadError& e) {
    if (std::string(e.what()).rfind(path, 0) != 0)
      pd_fuzz::Violation(std::string("MeshLoadError does not begin with the path: ") + e.what());
  } catch (const std::exception& e) {
    pd_fuzz::Violation(std::string("unexpected exception type: ") + e.what());
  }
  return 0;
}
