#include "pd_core/mesh/collision_model.h"

#include <cmath>
#include <numeric>

#include "pd_core/geometry/fibonacci_sphere.h"

namespace pd {
namespace {

std::vector<Vector3> FibonacciDirections(int n) {
  std::vector<Vector3> dirs(n);
  for (int i = 0; i < n; ++i) dirs[i] = FibonacciDirection(i, n);
  return dirs;
}

// The smallest vertex of each connected component (union-find over the
// triangles' vertices); vertices no triangle uses belong to no component.
std::vector<int> ComponentVertices(const TriangleMesh& mesh) {
  std::vector<int> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  auto unite = [&](int a, int b) {  // the smaller root stays the root
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
    unite(t[0], t[1]);
    unite(t[0], t[2]);
  }
  std::vector<int> reps;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (used[v] && find(v) == v) reps.push_back(v);
  return reps;
}

}  // namespace

std::shared_ptr<const CollisionModel> CollisionModel::Build(TriangleMesh mesh) {
  std::shared_ptr<CollisionModel> m(new CollisionModel());
  m->mesh_ = std::move(mesh);
  const TriangleMesh& M = m->mesh_;
  m->topology_ = ComputeTopology(M);
  m->bvh_ = Bvh(M);
  const int nt = M.num_triangles();
  m->face_normals_.resize(nt);
  for (int t = 0; t < nt; ++t) m->face_normals_[t] = FaceNormal(M, t);

  // Bounding sphere about the box centre: cheap and within sqrt(3) of optimal.
  const MeshBounds bounds = ComputeBounds(M);
  m->center_M_ = bounds.center();
  double r2 = 0.0;
  for (const Vector3& v : M.vertices) r2 = std::max(r2, (v - m->center_M_).squaredNorm());
  m->radius_ = std::sqrt(r2);
  m->centroid_M_ = SurfaceCentroid(M);

  // Support samples, and the vertices extreme in at least one sampled
  // direction (candidates for exact support queries).
  m->support_dirs_M_ = FibonacciDirections(512);
  m->support_values_.resize(m->support_dirs_M_.size());
  std::vector<char> is_hull(M.vertices.size(), 0);
  for (size_t i = 0; i < m->support_dirs_M_.size(); ++i) {
    const Vector3& u = m->support_dirs_M_[i];
    double best = -1e300;
    int arg = -1;
    for (int v = 0; v < M.num_vertices(); ++v) {
      const double h = u.dot(M.vertices[v]);
      if (h > best) best = h, arg = v;
    }
    m->support_values_[i] = best;
    if (arg >= 0) is_hull[arg] = 1;
  }
  for (int v = 0; v < M.num_vertices(); ++v)
    if (is_hull[v]) m->hull_vertices_.push_back(v);

  // Feature ownership: first triangle to reference a vertex or edge owns it.
  m->owned_features_.assign(nt, 0);
  std::vector<char> vertex_taken(M.vertices.size(), 0);
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = M.triangles[t][k];
      if (!vertex_taken[v]) {
        vertex_taken[v] = 1;
        m->owned_features_[t] |= static_cast<uint8_t>(1u << k);
      }
      const MeshEdge& e = m->topology_.edges[m->topology_.triangle_edges[t][k]];
      if (e.f0 == t) m->owned_features_[t] |= static_cast<uint8_t>(1u << (3 + k));
    }
  }
  m->component_vertices_ = ComponentVertices(M);
  m->inner_spheres_ = ComputeInnerSpheres(*m);  // needs the BVH and topology above
  return m;
}

double CollisionModel::SupportUpperBound(const Vector3& u_M) const {
  // 512 Fibonacci directions cover the sphere within ~0.1 rad; for any u the
  // true support exceeds the best candidate by at most 2 * angle * radius.
  constexpr double kCoveringAngle = 0.15;
  double best = -1e300;
  for (int v : hull_vertices_) best = std::max(best, u_M.dot(mesh_.vertices[v] - center_M_));
  return u_M.dot(center_M_) + best + 2.0 * kCoveringAngle * radius_;
}

size_t CollisionModel::MemoryBytes() const {
  size_t bytes = mesh_.vertices.capacity() * sizeof(Vector3) +
                 mesh_.triangles.capacity() * sizeof(Eigen::Vector3i);
  bytes += topology_.edges.capacity() * sizeof(MeshEdge) +
           topology_.triangle_edges.capacity() * sizeof(std::array<int, 3>);
  bytes += bvh_.MemoryBytes();
  bytes += face_normals_.capacity() * sizeof(Vector3);
  bytes += support_dirs_M_.capacity() * sizeof(Vector3) + support_values_.capacity() * sizeof(double);
  bytes += hull_vertices_.capacity() * sizeof(int) + owned_features_.capacity();
  bytes += component_vertices_.capacity() * sizeof(int);
  bytes += inner_spheres_.capacity() * sizeof(InnerSphere);
  return bytes;
}

}  // namespace pd
