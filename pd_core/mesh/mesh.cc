#include "pd_core/mesh/mesh.h"

namespace pd {

MeshBounds ComputeBounds(const TriangleMesh& mesh) {
  MeshBounds b;
  if (mesh.vertices.empty()) return b;
  b.min = b.max = mesh.vertices[0];
  for (const Vector3& v : mesh.vertices) {
    b.min = b.min.cwiseMin(v);
    b.max = b.max.cwiseMax(v);
  }
  return b;
}

Vector3 SurfaceCentroid(const TriangleMesh& mesh) {
  Vector3 sum = Vector3::Zero();
  double area_sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vector3& a = mesh.vertices[t[0]];
    const Vector3& b = mesh.vertices[t[1]];
    const Vector3& c = mesh.vertices[t[2]];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    sum += area * (a + b + c) / 3.0;
    area_sum += area;
  }
  if (area_sum <= 0.0) return ComputeBounds(mesh).center();
  return sum / area_sum;
}

Vector3 FaceNormal(const TriangleMesh& mesh, int t) {
  const auto& tri = mesh.triangles[t];
  const Vector3 n = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]])
                        .cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
  const double len = n.norm();
  return len > 0.0 ? Vector3(n / len) : Vector3::Zero();
}

}  // namespace pd
