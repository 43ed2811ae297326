#pragma once
// Loads a triangle mesh file (OBJ, STL, OFF, PLY; other formats assimp reads
// may work but are untested) into a TriangleMesh in the file's own frame M.
// Vertex coordinates are the file's numbers times `scale`, taken as metres; no
// unit conversion and no re-centring. Polygons are triangulated, node
// transforms applied, and vertices at identical positions welded (also across
// sub-meshes, and STL facets) so closed files give closed manifolds. Vertices
// keep the file's order; ones no triangle uses are dropped.
//
// Note: assimp stores coordinates as 32-bit floats, so file coordinates keep
// about 7 significant digits, and it also merges vertices closer than 1e-5
// file units.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "pd_core/mesh/mesh.h"
#include "pd_core/mesh/mesh_topology.h"

namespace pd {

struct MeshLoadOptions {
  double scale = 1.0;                    // uniform, file units -> metres; finite, > 0
  int64_t max_triangles = 5'000'000;     // larger files are refused before copying
  double max_abs_coordinate = 1e6;       // |coordinate| limit in metres, after scaling
};

// A file that cannot be turned into a usable mesh. what() begins with the file
// path and says what is wrong.
class MeshLoadError : public std::runtime_error {
 public:
  using runtime_error::runtime_error;
};

struct LoadedMesh {
  TriangleMesh mesh;      // name = path
  MeshTopology topology;  // of `mesh`
  // Non-fatal findings: dropped degenerate triangles, ignored points/lines,
  // open or non-manifold surface (PD works on soups; containment does not).
  std::vector<std::string> warnings;
};

// Throws MeshLoadError on a missing/unreadable/empty file, a header declaring
// more than the file holds, an assimp failure (including damage its OFF reader
// only logs: short files, out-of-range indices), no triangles, NaN/inf or too
// large coordinates, too many triangles, or bad options. Thread-safe.
LoadedMesh LoadMesh(const std::string& path, const MeshLoadOptions& options = {});

}  // namespace pd
