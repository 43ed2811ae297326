#include "pd_core/geometry/tessellate_geometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pd_core/geometry/make_shapes.h"

namespace pd {

TriangleMesh MakeCapsuleMesh(double radius, double half_length, int segments, int rings) {
  if (!(radius > 0.0) || !(half_length >= 0.0) || segments < 3 || rings < 1)
    throw std::invalid_argument("MakeCapsuleMesh: need radius > 0, half_length >= 0, segments >= 3, rings >= 1; got " +
                                std::to_string(radius) + ", " + std::to_string(half_length) + ", " +
                                std::to_string(segments) + ", " + std::to_string(rings));
  TriangleMesh m;
  m.name = "capsule";
  // Latitude rows from the top pole (excluded) to the bottom pole: rings per
  // hemisphere, the equator duplicated at z = +h and z = -h (if h > 0).
  std::vector<std::pair<double, double>> rows;  // (ring radius, z)
  for (int i = 1; i <= rings; ++i) {
    const double phi = 0.5 * M_PI * i / rings;  // from the pole
    rows.emplace_back(radius * std::sin(phi), half_length + radius * std::cos(phi));
  }
  if (half_length > 0.0) rows.emplace_back(radius, -half_length);
  for (int i = rings - 1; i >= 1; --i) {
    const double phi = 0.5 * M_PI * i / rings;
    rows.emplace_back(radius * std::sin(phi), -half_length - radius * std::cos(phi));
  }
  m.vertices.emplace_back(0, 0, half_length + radius);
  for (const auto& [r, z] : rows)
    for (int j = 0; j < segments; ++j) {
      const double a = 2.0 * M_PI * j / segments;
      m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  const int bottom = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0, 0, -half_length - radius);
  auto at = [&](int row, int j) { return 1 + row * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.triangles.emplace_back(0, at(0, j), at(0, j + 1));
  for (int row = 0; row + 1 < static_cast<int>(rows.size()); ++row)
    for (int j = 0; j < segments; ++j) {
      m.triangles.emplace_back(at(row, j), at(row + 1, j), at(row + 1, j + 1));
      m.triangles.emplace_back(at(row, j), at(row + 1, j + 1), at(row, j + 1));
    }
  const int last = static_cast<int>(rows.size()) - 1;
  for (int j = 0; j < segments; ++j) m.triangles.emplace_back(bottom, at(last, j + 1), at(last, j));
  return m;
}

namespace {

// Smallest distance from a face plane of `mesh` to the core (a point or a z
// segment of half length h), for a convex mesh around that core.
double MinFaceDistanceToCore(const TriangleMesh& mesh, double h) {
  double best = 1e300;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Vector3 n = FaceNormal(mesh, t);
    if (n.squaredNorm() < 0.5) continue;
    const double c = n.dot(mesh.vertices[mesh.triangles[t][0]]);
    best = std::min(best, c - std::abs(n.z()) * h);
  }
  return best;
}

// Scales the vertices radially away from the core (point or z segment) by s.
void ScaleAboutCore(TriangleMesh* mesh, double h, double s) {
  for (Vector3& v : mesh->vertices) {
    const Vector3 core(0, 0, std::clamp(v.z(), -h, h));
    v = core + s * (v - core);
  }
}

// Largest distance of a vertex from the core (point or z segment).
double MaxVertexDistanceFromCore(const TriangleMesh& mesh, double h) {
  double best = 0.0;
  for (const Vector3& v : mesh.vertices)
    best = std::max(best, (v - Vector3(0, 0, std::clamp(v.z(), -h, h))).norm());
  return best;
}

// Segments around a circle of radius r for a chord error below e*r,
// circumscribed: r (1/cos(pi/n) - 1) <= e r.
int SegmentsFor(double rel_chord_error) {
  const double a = std::acos(1.0 / (1.0 + rel_chord_error));
  return std::max(8, static_cast<int>(std::ceil(M_PI / a)));
}

// Grows the mesh about its core until every face plane is at least `radius`
// from the core, so the true shape lies inside.
void Circumscribe(TriangleMesh* mesh, double h, double radius) {
  for (int pass = 0; pass < 4; ++pass) {
    const double d = MinFaceDistanceToCore(*mesh, h);
    if (d >= radius) return;
    ScaleAboutCore(mesh, h, radius / d * (1.0 + 1e-12));
  }
}

}  // namespace

TriangleMesh TessellateGeometry(const Geometry& g, double rel_chord_error) {
  if (!(rel_chord_error > 0.0 && rel_chord_error < 1.0))
    throw std::invalid_argument("TessellateGeometry: rel_chord_error must be in (0, 1), got " +
                                std::to_string(rel_chord_error));
  TriangleMesh mesh;
  switch (g.kind()) {
    case ShapeKind::kHalfSpace:
      throw std::invalid_argument("TessellateGeometry: a half-space has no finite mesh");
    case ShapeKind::kBox: return pd::MakeBox(g.box().half_extents);
    case ShapeKind::kConvexMesh:
    case ShapeKind::kMesh: return g.model()->mesh();
    case ShapeKind::kSphere: {
      // Finer icospheres until the circumscribed mesh is within the error.
      const double r = g.sphere().radius;
      for (int k = 0; k <= 6; ++k) {
        mesh = MakeIcosphere(r, k);
        Circumscribe(&mesh, 0.0, r);
        if (MaxVertexDistanceFromCore(mesh, 0.0) - r <= rel_chord_error * r) break;
      }
      break;
    }
    case ShapeKind::kCapsule: {
      const double r = g.capsule().radius, h = g.capsule().half_length;
      for (int n = SegmentsFor(rel_chord_error); n < 4096; n = n * 5 / 4 + 1) {
        mesh = MakeCapsuleMesh(r, h, n, std::max(2, n / 4));
        Circumscribe(&mesh, h, r);
        if (MaxVertexDistanceFromCore(mesh, h) - r <= rel_chord_error * r) break;
      }
      break;
    }
    case ShapeKind::kCylinder: {
      const int n = SegmentsFor(rel_chord_error);
      const double r = g.cylinder().radius / std::cos(M_PI / n);
      mesh = MakeCylinder(r, 2.0 * g.cylinder().half_length, n);
      break;
    }
  }
  mesh.name = g.Describe() + " tessellated";
  return mesh;
}

double TessellationError(const Geometry& g, const TriangleMesh& mesh) {
  double e = 0.0;
  for (const Vector3& v : mesh.vertices) {
    switch (g.kind()) {
      case ShapeKind::kSphere: e = std::max(e, v.norm() - g.sphere().radius); break;
      case ShapeKind::kCapsule: {
        const double h = g.capsule().half_length;
        e = std::max(e, (v - Vector3(0, 0, std::clamp(v.z(), -h, h))).norm() - g.capsule().radius);
        break;
      }
      case ShapeKind::kCylinder: e = std::max(e, std::hypot(v.x(), v.y()) - g.cylinder().radius); break;
      default: return 0.0;
    }
  }
  return e;
}

}  // namespace pd
