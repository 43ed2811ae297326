#pragma once
// An indexed triangle mesh in its own frame M. Vertex coordinates are the file's
// coordinates multiplied by the uniform load scale, in metres; a pose X_WM places
// vertex v at X_WM * v in world. Nothing is re-centred.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "pd_core/geometry/pose.h"

namespace pd {

struct TriangleMesh {
  std::vector<Vector3> vertices;           // p_MV, metres
  std::vector<Eigen::Vector3i> triangles;  // counter-clockwise seen from outside
  std::string name;                        // file path or generator name, for messages

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
};

// Axis-aligned bounds in the mesh frame.
struct MeshBounds {
  Vector3 min = Vector3::Zero();
  Vector3 max = Vector3::Zero();
  Vector3 center() const { return 0.5 * (min + max); }
  double diagonal() const { return (max - min).norm(); }
};
MeshBounds ComputeBounds(const TriangleMesh& mesh);

// Area-weighted centroid of the surface, in the mesh frame.
Vector3 SurfaceCentroid(const TriangleMesh& mesh);

// Unit outward face normal (zero for a degenerate triangle).
Vector3 FaceNormal(const TriangleMesh& mesh, int t);

}  // namespace pd
