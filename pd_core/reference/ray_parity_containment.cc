#include "pd_core/reference/ray_parity_containment.h"

#include <cmath>
#include <random>

namespace pd {
namespace reference {
namespace {

// Parity of the crossings of the ray x + t d (t > 0) with the mesh. *clean is
// cleared when the ray passes near an edge or vertex, runs parallel to a
// triangle it may graze, or x is on the surface: then the count is unreliable.
bool RayParityOdd(const Vector3& x, const Vector3& d, const PlacedMesh& m, double eps_len,
                  bool* clean) {
  constexpr double kBaryTol = 1e-9;
  bool odd = false;
  *clean = true;
  for (const auto& t : *m.triangles) {
    const Vector3& v0 = m.p_OV[t[0]];
    const Vector3 e1 = m.p_OV[t[1]] - v0;
    const Vector3 e2 = m.p_OV[t[2]] - v0;
    const Vector3 pvec = d.cross(e2);
    const double det = e1.dot(pvec);
    const Vector3 tvec = x - v0;
    if (std::abs(det) <= 1e-14 * e1.norm() * e2.norm()) {
      // Parallel to the plane: it can only graze the triangle, and only if x
      // is in that plane.
      const Vector3 n = e1.cross(e2);
      const double n_norm = n.norm();
      if (n_norm > 0.0 && std::abs(n.dot(tvec)) <= eps_len * n_norm) *clean = false;
      continue;
    }
    const double inv = 1.0 / det;
    const double b1 = tvec.dot(pvec) * inv;
    if (b1 < -kBaryTol || b1 > 1.0 + kBaryTol) continue;
    const Vector3 qvec = tvec.cross(e1);
    const double b2 = d.dot(qvec) * inv;
    if (b2 < -kBaryTol || b1 + b2 > 1.0 + kBaryTol) continue;
    const double s = e2.dot(qvec) * inv;
    if (s < -eps_len) continue;
    if (b1 < kBaryTol || b2 < kBaryTol || b1 + b2 > 1.0 - kBaryTol || s <= eps_len) {
      *clean = false;
      continue;
    }
    odd = !odd;
  }
  return odd;
}

// Majority of three clean rays in fixed pseudo-random directions.
bool PointInside(const Vector3& x, const PlacedMesh& m, double eps_len) {
  std::mt19937 rng(20240611u);
  std::normal_distribution<double> gauss;
  int votes_in = 0, votes_out = 0, dirty_in = 0, dirty_out = 0;
  for (int attempt = 0; attempt < 24 && votes_in + votes_out < 3; ++attempt) {
    Vector3 d(gauss(rng), gauss(rng), gauss(rng));
    d.normalize();
    bool clean = true;
    const bool odd = RayParityOdd(x, d, m, eps_len, &clean);
    if (clean) {
      (odd ? votes_in : votes_out)++;
    } else {
      (odd ? dirty_in : dirty_out)++;
    }
  }
  if (votes_in + votes_out == 0) return dirty_in > dirty_out;
  return votes_in > votes_out;
}

}  // namespace

bool Contained(const PairGeometry& g, const Vector3& t_W) {
  if (g.S.closed) {
    for (int v : g.P.component_vertices) {
      if (PointInside(g.P.p_OV[v] + t_W, g.S, g.eps_len)) return true;
    }
  }
  if (g.P.closed) {
    for (int v : g.S.component_vertices) {
      if (PointInside(g.S.p_OV[v] - t_W, g.P, g.eps_len)) return true;
    }
  }
  return false;
}

}  // namespace reference
}  // namespace pd
