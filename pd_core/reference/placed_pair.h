#pragma once
// The reference's meshes placed in world and re-centred on a common origin
// O, so tolerances scale with the pair and not with its distance from the
// world origin. Part of the slow independent reference (reference_pd.h): no
// code shared with the fast path.
#include <limits>
#include <vector>

#include "pd_core/geometry/pose.h"
#include "pd_core/mesh/mesh.h"

namespace pd {
namespace reference {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct PlacedMesh {
  std::vector<Vector3> p_OV;  // vertex positions relative to O, world axes (m)
  const std::vector<Eigen::Vector3i>* triangles = nullptr;
  std::vector<int> component_vertices;  // one vertex of each connected component
  bool closed = false;
  int num_triangles() const { return static_cast<int>(triangles->size()); }
};

struct PairGeometry {
  PlacedMesh P, S;
  double eps_len = 0.0;  // absolute length tolerance of feature tests (m)
  double size = 0.0;     // sum of bounding-sphere radii (m)
};

// Places both meshes around the centre of their joint bounds; eps_len is
// kRelativeLengthTol (placed_pair.cc) of their extent there.
PairGeometry MakePair(const TriangleMesh& probe, const Isometry3& X_WP, bool probe_closed,
                      const TriangleMesh& scene, const Isometry3& X_WS, bool scene_closed);

}  // namespace reference
}  // namespace pd
