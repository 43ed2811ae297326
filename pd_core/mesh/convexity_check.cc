#include "pd_core/mesh/convexity_check.h"

#include <sstream>

namespace pd {

ConvexityReport CheckConvexity(const CollisionModel& model, double rel_tol) {
  ConvexityReport report;
  const TriangleMesh& mesh = model.mesh();
  const std::string name = mesh.name.empty() ? std::string("(unnamed)") : mesh.name;
  std::ostringstream why;
  if (mesh.num_triangles() < 4 || !model.closed()) {
    why << "mesh '" << name << "' declared convex is not a closed manifold ("
        << model.topology().Describe() << ")";
    report.message = why.str();
    return report;
  }
  for (const auto& t : mesh.triangles) {
    const Vector3& a = mesh.vertices[t[0]];
    report.volume += a.dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  const double r = model.radius();
  if (!(report.volume > 1e-9 * r * r * r)) {
    why << "mesh '" << name << "' declared convex has non-positive volume " << report.volume
        << " m^3 (flat or inward-oriented triangles)";
    report.message = why.str();
    return report;
  }
  const auto& normals = model.face_normals();
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Vector3& n = normals[f];
    if (n.squaredNorm() < 0.5) continue;  // degenerate triangle: no plane
    const double d = n.dot(mesh.vertices[mesh.triangles[f][0]]);
    for (int v : model.hull_vertices()) {
      const double out = n.dot(mesh.vertices[v]) - d;
      if (out > report.max_violation) {
        report.max_violation = out;
        report.worst_vertex = v;
        report.worst_face = f;
      }
    }
  }
  report.relative_violation = report.max_violation / r;
  report.convex = report.relative_violation <= rel_tol;
  if (!report.convex) {
    why << "mesh '" << name << "' declared convex is not convex: vertex " << report.worst_vertex
        << " lies " << report.max_violation << " m (" << report.relative_violation
        << " of its bounding radius; allowed " << rel_tol << ") outside the plane of triangle "
        << report.worst_face;
    report.message = why.str();
  }
  return report;
}

}  // namespace pd
