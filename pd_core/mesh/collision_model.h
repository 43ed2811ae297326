#pragma once
// Everything precomputed for one mesh so that proximity and PD queries are
// fast: topology, face normals, a bounding-volume hierarchy and the support
// directions used by the maximally-clear initialiser. Immutable after Build(),
// so one model can be shared by many solvers on many threads.
#include <cstdint>
#include <memory>
#include <vector>

#include "pd_core/proximity/bvh.h"
#include "pd_core/mesh/inner_spheres.h"
#include "pd_core/mesh/mesh.h"
#include "pd_core/mesh/mesh_topology.h"

namespace pd {

class CollisionModel {
 public:
  // Builds all acceleration data for `mesh` (coordinates kept as given).
  static std::shared_ptr<const CollisionModel> Build(TriangleMesh mesh);

  const TriangleMesh& mesh() const { return mesh_; }
  const MeshTopology& topology() const { return topology_; }
  const Bvh& bvh() const { return bvh_; }
  const std::vector<Vector3>& face_normals() const { return face_normals_; }
  // Closed manifold: solid containment is meaningful.
  bool closed() const { return topology_.closed(); }
  // Bounding sphere in the mesh frame M (m).
  const Vector3& center() const { return center_M_; }
  double radius() const { return radius_; }
  // Area-weighted surface centroid in M (m).
  const Vector3& centroid() const { return centroid_M_; }
  // Convex-hull support samples: support_[i] = max_v dir_i·v over the mesh,
  // for the unit directions support_dirs_[i] in M.
  const std::vector<Vector3>& support_directions() const { return support_dirs_M_; }
  const std::vector<double>& support_values() const { return support_values_; }
  // Indices of vertices that can be extreme in some direction (convex-hull
  // candidates), used for exact support-function queries.
  const std::vector<int>& hull_vertices() const { return hull_vertices_; }
  // An upper bound on max_v u·v for a unit direction u_M (m): exact over the
  // hull candidates plus a slack covering vertices no sampled direction
  // picked (2 * covering angle * radius), so a plane placed there separates.
  double SupportUpperBound(const Vector3& u_M) const;

  // Per triangle, which of its features it owns (bit k: vertex tri[k]; bit
  // 3+k: edge triangle_edges[k]). Each vertex and edge has exactly one owner,
  // so pair traversals visit every feature pair once without a hash set.
  const std::vector<uint8_t>& owned_features() const { return owned_features_; }

  // One vertex of each connected component (triangles linked through shared
  // vertices): the smallest vertex index of the component, in increasing
  // order. Where two meshes' surfaces do not cross, each component lies
  // wholly inside or wholly outside the other's solid, so containment tests
  // one vertex per component (pd_core/proximity/solid_containment.h).
  const std::vector<int>& component_vertices() const { return component_vertices_; }

  // Balls inside the solid (closed meshes only; inner_spheres.h): a cold
  // search's deep collision tests are settled by their overlap first.
  const std::vector<InnerSphere>& inner_spheres() const { return inner_spheres_; }

  // Heap bytes held by the model (mesh, topology, BVH, precomputation).
  size_t MemoryBytes() const;

 private:
  friend struct ModelCacheAccess;  // pd_core/mesh/model_cache.cc (de)serialises every field
  CollisionModel() = default;
  TriangleMesh mesh_;
  MeshTopology topology_;
  Bvh bvh_;
  std::vector<Vector3> face_normals_;
  Vector3 center_M_ = Vector3::Zero();
  double radius_ = 0.0;
  Vector3 centroid_M_ = Vector3::Zero();
  std::vector<Vector3> support_dirs_M_;
  std::vector<double> support_values_;
  std::vector<int> hull_vertices_;
  std::vector<uint8_t> owned_features_;
  std::vector<int> component_vertices_;
  std::vector<InnerSphere> inner_spheres_;
};

}  // namespace pd
