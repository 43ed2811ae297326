#include "pd_core/point_in_mesh.h"

#include <array>
#include <cmath>

namespace pd {
namespace {

// Slab test in the box's own frame.
bool RayHitsBox(const Vector3& o, const Vector3& d, const BvhNode& n) {
  const Vector3 o_B = n.R_MB.transpose() * (o - n.center_M);
  const Vector3 d_B = n.R_MB.transpose() * d;
  double t0 = 0.0, t1 = 1e300;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d_B[k]) < 1e-300) {
      if (std::abs(o_B[k]) > n.half_B[k]) return false;
      continue;
    }
    const double inv = 1.0 / d_B[k];
    double a = (-n.half_B[k] - o_B[k]) * inv, b = (n.half_B[k] - o_B[k]) * inv;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

// Returns crossings count, or -1 if the ray passed too close to an edge or
// vertex (or along a face) to be trusted.
int CountCrossings(const CollisionModel& model, const Vector3& o, const Vector3& d) {
  const Bvh& bvh = model.bvh();
  const auto& mesh = model.mesh();
  std::array<int, 128> stack;
  int top = 0;
  stack[top++] = 0;
  int crossings = 0;
  while (top > 0) {
    const int i = stack[--top];
    const BvhNode& n = bvh.nodes()[i];
    if (!RayHitsBox(o, d, n)) continue;
    if (!n.is_leaf()) {
      stack[top++] = n.right_or_first;
      stack[top++] = i + 1;
      continue;
    }
    for (int k = 0; k < n.count; ++k) {
      const auto& tri = mesh.triangles[bvh.order()[n.right_or_first + k]];
      const Vector3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]],
                    &c = mesh.vertices[tri[2]];
      const Vector3 e1 = b - a, e2 = c - a;
      const Vector3 pv = d.cross(e2);
      const double det = e1.dot(pv);
      const double scale = e1.norm() * e2.norm();
      const Vector3 tv = o - a;
      if (std::abs(det) <= 1e-12 * scale) {
        // Ray parallel to the face: unsafe only if it lies in its plane.
        if (std::abs(tv.dot(e1.cross(e2))) <= 1e-12 * scale * tv.norm()) return -1;
        continue;
      }
      const double inv = 1.0 / det;
      const double u = tv.dot(pv) * inv;
      const Vector3 qv = tv.cross(e1);
      const double v = d.dot(qv) * inv;
      const double s = e2.dot(qv) * inv;
      const double w = 1.0 - u - v;
      constexpr double kGraze = 1e-9;
      if (u < -kGraze || v < -kGraze || w < -kGraze) continue;
      if (s < 0) continue;
      if (u < kGraze || v < kGraze || w < kGraze) return -1;  // grazing an edge
      ++crossings;
    }
  }
  return crossings;
}

}  // namespace

bool PointInsideMesh(const CollisionModel& model, const Vector3& p_M) {
  if (model.bvh().empty()) return false;
  const BvhNode& root = model.bvh().nodes()[0];
  if (((root.R_MB.transpose() * (p_M - root.center_M)).cwiseAbs() - root.half_B).maxCoeff() > 0)
    return false;
  // Irrational-looking directions make grazing unlikely; retry on grazes.
  static const Vector3 kDirs[7] = {
      Vector3(0.5773, 0.5774, 0.5776), Vector3(-0.3141, 0.8172, 0.4831),
      Vector3(0.7071, -0.2236, -0.6708), Vector3(-0.6180, -0.5878, 0.5213),
      Vector3(0.1234, -0.9012, -0.4155), Vector3(-0.8415, 0.3090, -0.4432),
      Vector3(0.2718, 0.3142, -0.9093)};
  int inside_votes = 0, clean = 0;
  for (const Vector3& dir : kDirs) {
    const int c = CountCrossings(model, p_M, dir.normalized());
    if (c < 0) continue;
    ++clean;
    inside_votes += (c % 2 == 1);
    if (inside_votes == 2 || clean - inside_votes == 2) break;  // majority of 3
  }
  return clean > 0 && 2 * inside_votes > clean;
}

}  // namespace pd
