#include "pd_core/geometry/make_shapes.h"

#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pd {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

bool Positive(double x) { return std::isfinite(x) && x > 0.0; }

// Quad a-b-c-d counter-clockwise from outside, as two triangles.
void AddQuad(TriangleMesh* mesh, int a, int b, int c, int d) {
  mesh->triangles.emplace_back(a, b, c);
  mesh->triangles.emplace_back(a, c, d);
}

// Closed tube over a periodic grid: vertex (i, j) = i * cols + j, rows and
// columns both wrap. Cells are CCW from outside when d/drow x d/dcol points out.
void AddWrappedGrid(TriangleMesh* mesh, int rows, int cols) {
  for (int i = 0; i < rows; ++i) {
    const int i1 = (i + 1) % rows;
    for (int j = 0; j < cols; ++j) {
      const int j1 = (j + 1) % cols;
      AddQuad(mesh, i * cols + j, i1 * cols + j, i1 * cols + j1, i * cols + j1);
    }
  }
}

}  // namespace

TriangleMesh MakeBox(const Vector3& half_extents) {
  Require(Positive(half_extents.x()) && Positive(half_extents.y()) && Positive(half_extents.z()),
          "MakeBox: half extents must be finite and > 0");
  TriangleMesh mesh;
  mesh.name = "box";
  // Vertex k has coordinate signs from its bits: x = bit 0, y = bit 1, z = bit 2.
  for (int k = 0; k < 8; ++k) {
    mesh.vertices.emplace_back((k & 1 ? 1 : -1) * half_extents.x(),
                               (k & 2 ? 1 : -1) * half_extents.y(),
                               (k & 4 ? 1 : -1) * half_extents.z());
  }
  AddQuad(&mesh, 0, 4, 6, 2);  // -x
  AddQuad(&mesh, 1, 3, 7, 5);  // +x
  AddQuad(&mesh, 0, 1, 5, 4);  // -y
  AddQuad(&mesh, 2, 6, 7, 3);  // +y
  AddQuad(&mesh, 0, 2, 3, 1);  // -z
  AddQuad(&mesh, 4, 5, 7, 6);  // +z
  return mesh;
}

TriangleMesh TranslatedMesh(TriangleMesh mesh, const Vector3& p_M) {
  for (Vector3& v : mesh.vertices) v += p_M;
  return mesh;
}

TriangleMesh JoinedMeshes(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const int base = m.num_vertices();
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles) m.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  return m;
}

TriangleMesh MakeIcosphere(double radius, int subdivisions) {
  Require(Positive(radius), "MakeIcosphere: radius must be finite and > 0");
  Require(subdivisions >= 0 && subdivisions <= 8, "MakeIcosphere: subdivisions must be in [0, 8]");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vector3> unit = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                               {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                               {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vector3& v : unit) v.normalize();
  std::vector<Eigen::Vector3i> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    // Shared edge midpoints keep the surface welded.
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoint.emplace(key, static_cast<int>(unit.size()));
      if (inserted) unit.push_back((unit[a] + unit[b]).normalized());
      return it->second;
    };
    std::vector<Eigen::Vector3i> finer;
    finer.reserve(faces.size() * 4);
    for (const Eigen::Vector3i& f : faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      finer.emplace_back(f[0], ab, ca);
      finer.emplace_back(f[1], bc, ab);
      finer.emplace_back(f[2], ca, bc);
      finer.emplace_back(ab, bc, ca);
    }
    faces = std::move(finer);
  }
  TriangleMesh mesh;
  mesh.name = "icosphere";
  mesh.vertices.reserve(unit.size());
  for (const Vector3& u : unit) mesh.vertices.push_back(radius * u);
  mesh.triangles = std::move(faces);
  return mesh;
}

TriangleMesh MakeCylinder(double radius, double length, int segments) {
  Require(Positive(radius) && Positive(length), "MakeCylinder: radius and length must be > 0");
  Require(segments >= 3, "MakeCylinder: segments must be >= 3");
  TriangleMesh mesh;
  mesh.name = "cylinder";
  const double h = 0.5 * length;
  // Vertices: bottom ring 0..n-1, top ring n..2n-1, bottom centre, top centre.
  const int n = segments;
  for (int z = 0; z < 2; ++z) {
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      mesh.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), z ? h : -h);
    }
  }
  const int bottom = 2 * n, top = 2 * n + 1;
  mesh.vertices.emplace_back(0.0, 0.0, -h);
  mesh.vertices.emplace_back(0.0, 0.0, h);
  for (int i = 0; i < n; ++i) {
    const int i1 = (i + 1) % n;
    mesh.triangles.emplace_back(bottom, i1, i);
    mesh.triangles.emplace_back(top, n + i, n + i1);
    AddQuad(&mesh, i, i1, n + i1, n + i);
  }
  return mesh;
}

TriangleMesh MakeTorus(double major_radius, double minor_radius, int major_segments,
                       int minor_segments) {
  Require(Positive(major_radius) && Positive(minor_radius) && minor_radius < major_radius,
          "MakeTorus: need 0 < minor_radius < major_radius");
  Require(major_segments >= 3 && minor_segments >= 3, "MakeTorus: segments must be >= 3");
  TriangleMesh mesh;
  mesh.name = "torus";
  for (int i = 0; i < major_segments; ++i) {
    const double u = 2.0 * M_PI * i / major_segments;
    for (int j = 0; j < minor_segments; ++j) {
      const double v = 2.0 * M_PI * j / minor_segments;
      const double rho = major_radius + minor_radius * std::cos(v);
      mesh.vertices.emplace_back(rho * std::cos(u), rho * std::sin(u), minor_radius * std::sin(v));
    }
  }
  // d/du x d/dv points away from the tube centre.
  AddWrappedGrid(&mesh, major_segments, minor_segments);
  return mesh;
}

TriangleMesh MakeTorusKnot(int p, int q, double tube_radius, double scale, int segments,
                           int tube_segments) {
  Require(p >= 1 && q >= 1 && std::gcd(p, q) == 1, "MakeTorusKnot: p, q must be coprime and >= 1");
  Require(Positive(tube_radius) && Positive(scale), "MakeTorusKnot: radii must be > 0");
  Require(segments >= 3 && tube_segments >= 3, "MakeTorusKnot: segments must be >= 3");
  const double R = scale, r = 0.5 * scale;
  // Centre line c(t) on the torus, and the torus surface normal there, which
  // is perpendicular to c'(t) and periodic, so the tube closes without twist.
  auto centre = [&](double t, Vector3* normal) {
    const double u = p * t, v = q * t;
    const Vector3 radial(std::cos(u), std::sin(u), 0.0);
    if (normal) *normal = std::cos(v) * radial + std::sin(v) * Vector3::UnitZ();
    return Vector3((R + r * std::cos(v)) * radial + r * std::sin(v) * Vector3::UnitZ());
  };

  // Refuse a tube that would cut through itself: points of the centre line
  // more than half a tube circumference apart along it must stay 2 radii apart,
  // and the line must not bend tighter than the tube radius.
  const int n = 4 * segments;
  std::vector<Vector3> c(n);
  std::vector<double> s(n + 1, 0.0);  // arc length to sample i
  for (int i = 0; i < n; ++i) c[i] = centre(2.0 * M_PI * i / n, nullptr);
  for (int i = 0; i < n; ++i) s[i + 1] = s[i] + (c[(i + 1) % n] - c[i]).norm();
  const double length = s[n];
  for (int i = 0; i < n; ++i) {
    // Curvature from the circle through three consecutive samples.
    const Vector3 a = c[i] - c[(i + n - 1) % n], b = c[(i + 1) % n] - c[i];
    const double curvature = 2.0 * a.cross(b).norm() / (a.norm() * b.norm() * (a + b).norm());
    Require(curvature * tube_radius < 1.0,
            "MakeTorusKnot: tube_radius exceeds the knot's radius of curvature");
    for (int j = i + 1; j < n; ++j) {
      const double along = std::min(s[j] - s[i], length - (s[j] - s[i]));
      if (along > M_PI * tube_radius && (c[j] - c[i]).norm() < 2.0 * tube_radius)
        throw std::invalid_argument("MakeTorusKnot: tube_radius too large, the tube would self-intersect");
    }
  }

  TriangleMesh mesh;
  mesh.name = "torus_knot_" + std::to_string(p) + "_" + std::to_string(q);
  for (int i = 0; i < segments; ++i) {
    const double t = 2.0 * M_PI * i / segments;
    Vector3 n_M;
    const Vector3 c_M = centre(t, &n_M);
    const Vector3 tangent = (centre(t + 1e-6, nullptr) - centre(t - 1e-6, nullptr)).normalized();
    const Vector3 b_M = n_M.cross(tangent);  // tangent x (cos n + sin b) points outward
    for (int j = 0; j < tube_segments; ++j) {
      const double phi = 2.0 * M_PI * j / tube_segments;
      mesh.vertices.push_back(c_M + tube_radius * (std::cos(phi) * n_M + std::sin(phi) * b_M));
    }
  }
  AddWrappedGrid(&mesh, segments, tube_segments);
  return mesh;
}

TriangleMesh MakeUSlot(const Vector3& outer_half_extents, double slot_width, double slot_depth) {
  const double hx = outer_half_extents.x(), hy = outer_half_extents.y(), hz = outer_half_extents.z();
  Require(Positive(hx) && Positive(hy) && Positive(hz), "MakeUSlot: half extents must be > 0");
  Require(Positive(slot_width) && slot_width < 2.0 * hy,
          "MakeUSlot: need 0 < slot_width < 2 * half_extents.y");
  Require(Positive(slot_depth) && slot_depth < 2.0 * hz,
          "MakeUSlot: need 0 < slot_depth < 2 * half_extents.z");
  const double w = 0.5 * slot_width, floor_z = hz - slot_depth;
  // U-shaped cross-section (y, z), counter-clockwise seen from +x.
  const std::array<std::array<double, 2>, 8> u = {{{-hy, -hz},
                                                    {hy, -hz},
                                                    {hy, hz},
                                                    {w, hz},
                                                    {w, floor_z},
                                                    {-w, floor_z},
                                                    {-w, hz},
                                                    {-hy, hz}}};
  // Its triangulation with no extra vertices (checked CCW for w < hy, floor_z > -hz).
  const std::array<std::array<int, 3>, 6> cap = {
      {{0, 1, 4}, {1, 2, 3}, {1, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 7}}};
  TriangleMesh mesh;
  mesh.name = "u_slot";
  for (double x : {-hx, hx}) {
    for (const auto& yz : u) mesh.vertices.emplace_back(x, yz[0], yz[1]);
  }
  // Vertices 0..7 at x = -hx (cap seen from -x: reversed), 8..15 at x = +hx.
  for (const auto& t : cap) {
    mesh.triangles.emplace_back(8 + t[0], 8 + t[1], 8 + t[2]);
    mesh.triangles.emplace_back(t[0], t[2], t[1]);
  }
  for (int i = 0; i < 8; ++i) {
    const int i1 = (i + 1) % 8;
    AddQuad(&mesh, i, i1, 8 + i1, 8 + i);
  }
  return mesh;
}

TriangleMesh MakeThinPlate(double half_x, double half_y, double half_thickness) {
  TriangleMesh mesh = MakeBox(Vector3(half_x, half_y, half_thickness));
  mesh.name = "thin_plate";
  return mesh;
}

}  // namespace pd

// ---- Shapes for the haptic demo scenes (added with haptics/) ----

namespace pd {
namespace {

// Point on the boundary of the axis-aligned rectangle [-hx, hx] x [-hy, hy]
// at parametric angle a: the square's boundary point along (cos a, sin a),
// stretched. Corners fall at a = pi/4 + k pi/2.
Eigen::Vector2d RectangleBoundaryPoint(double hx, double hy, double a) {
  const double c = std::cos(a), s = std::sin(a);
  const double m = std::max(std::abs(c), std::abs(s));
  return {hx * c / m, hy * s / m};
}

// Prism over a counter-clockwise polygon (seen from +z) with its cap
// triangulation `cap` (CCW from +z), z in [z0, z1]. Bottom ring first.
TriangleMesh ExtrudePolygon(const std::vector<Eigen::Vector2d>& polygon,
                            const std::vector<std::array<int, 3>>& cap, double z0, double z1) {
  TriangleMesh mesh;
  const int n = static_cast<int>(polygon.size());
  for (double z : {z0, z1}) {
    for (const Eigen::Vector2d& p : polygon) mesh.vertices.emplace_back(p.x(), p.y(), z);
  }
  for (const auto& t : cap) {
    mesh.triangles.emplace_back(n + t[0], n + t[1], n + t[2]);  // top, +z
    mesh.triangles.emplace_back(t[0], t[2], t[1]);              // bottom, -z
  }
  for (int i = 0; i < n; ++i) {
    const int i1 = (i + 1) % n;
    AddQuad(&mesh, i, i1, n + i1, n + i);
  }
  return mesh;
}

}  // namespace

TriangleMesh MakeCup(double outer_radius, double height, double wall_thickness,
                     double floor_thickness, int segments) {
  Require(Positive(outer_radius) && Positive(height), "MakeCup: radius and height must be > 0");
  Require(Positive(wall_thickness) && wall_thickness < outer_radius,
          "MakeCup: need 0 < wall_thickness < outer_radius");
  Require(Positive(floor_thickness) && floor_thickness < height,
          "MakeCup: need 0 < floor_thickness < height");
  Require(segments >= 3, "MakeCup: segments must be >= 3");
  const int n = segments;
  const double h = 0.5 * height, r_in = outer_radius - wall_thickness;
  const double z_floor = -h + floor_thickness;
  TriangleMesh mesh;
  mesh.name = "cup";
  // Rings: 0 outer bottom, 1 outer top, 2 inner top, 3 inner floor.
  const std::array<std::pair<double, double>, 4> rings = {
      {{outer_radius, -h}, {outer_radius, h}, {r_in, h}, {r_in, z_floor}}};
  for (const auto& [r, z] : rings) {
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      mesh.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  }
  auto v = [n](int ring, int i) { return ring * n + (i % n); };
  for (int i = 0; i < n; ++i) {
    AddQuad(&mesh, v(0, i), v(0, i + 1), v(1, i + 1), v(1, i));      // outer wall
    AddQuad(&mesh, v(1, i), v(1, i + 1), v(2, i + 1), v(2, i));      // rim, +z
    AddQuad(&mesh, v(3, i), v(2, i), v(2, i + 1), v(3, i + 1));      // inner wall, inward
  }
  // Base and floor: zig-zag strips across the polygon rather than fans. A fan
  // puts n slivers around one centre vertex, and a flat tool resting there
  // meets all of them at once (many near-contact feature pairs, slow PD).
  int lo = 0, hi = n - 1;
  for (bool left = true; hi - lo >= 2; left = !left) {
    const int a = lo, b = left ? lo + 1 : hi - 1, c = hi;  // CCW seen from +z
    mesh.triangles.emplace_back(v(3, a), v(3, b), v(3, c));  // inner floor, +z
    mesh.triangles.emplace_back(v(0, a), v(0, c), v(0, b));  // base, -z
    if (left) {
      ++lo;
    } else {
      --hi;
    }
  }
  return mesh;
}

TriangleMesh MakeBlockWithHole(const Vector3& half_extents, double hole_half_width,
                               bool round_hole, int segments) {
  const double hx = half_extents.x(), hy = half_extents.y(), hz = half_extents.z();
  Require(Positive(hx) && Positive(hy) && Positive(hz),
          "MakeBlockWithHole: half extents must be > 0");
  Require(Positive(hole_half_width) && hole_half_width < std::min(hx, hy),
          "MakeBlockWithHole: need 0 < hole_half_width < min(half_extents.x, half_extents.y)");
  Require(segments >= (round_hole ? 8 : 4) && segments % 4 == 0,
          "MakeBlockWithHole: segments must be a multiple of 4 (>= 8 for a round hole)");
  const int n = segments;
  TriangleMesh mesh;
  mesh.name = round_hole ? "block_with_round_hole" : "block_with_square_hole";
  // Rings at the same parametric angles (starting at a corner, so all four
  // outer corners are vertices): 0 outer bottom, 1 outer top, 2 hole top,
  // 3 hole bottom.
  for (int ring = 0; ring < 4; ++ring) {
    const double z = (ring == 1 || ring == 2) ? hz : -hz;
    for (int i = 0; i < n; ++i) {
      const double a = M_PI / 4.0 + 2.0 * M_PI * i / n;
      Eigen::Vector2d p;
      if (ring < 2) {
        p = RectangleBoundaryPoint(hx, hy, a);
      } else if (round_hole) {
        p = hole_half_width * Eigen::Vector2d(std::cos(a), std::sin(a));
      } else {
        p = RectangleBoundaryPoint(hole_half_width, hole_half_width, a);
      }
      mesh.vertices.emplace_back(p.x(), p.y(), z);
    }
  }
  auto v = [n](int ring, int i) { return ring * n + (i % n); };
  for (int i = 0; i < n; ++i) {
    AddQuad(&mesh, v(0, i), v(0, i + 1), v(1, i + 1), v(1, i));  // outer wall
    AddQuad(&mesh, v(1, i), v(1, i + 1), v(2, i + 1), v(2, i));  // top face, +z
    AddQuad(&mesh, v(3, i), v(2, i), v(2, i + 1), v(3, i + 1));  // hole wall, toward axis
    AddQuad(&mesh, v(0, i), v(3, i), v(3, i + 1), v(0, i + 1));  // bottom face, -z
  }
  return mesh;
}

TriangleMesh MakeLRod(double arm_x, double arm_y, double width, double thickness) {
  Require(Positive(width) && Positive(thickness), "MakeLRod: width and thickness must be > 0");
  Require(std::isfinite(arm_x) && std::isfinite(arm_y) && arm_x > 0.5 * width &&
              arm_y > 0.5 * width,
          "MakeLRod: need arm_x > width / 2 and arm_y > width / 2");
  const double w = 0.5 * width;
  // The L outline, counter-clockwise; vertex 3 is the reflex corner and every
  // cap triangle fans from it.
  const std::vector<Eigen::Vector2d> outline = {{-w, -w}, {arm_x, -w}, {arm_x, w},
                                                {w, w},   {w, arm_y}, {-w, arm_y}};
  const std::vector<std::array<int, 3>> cap = {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}};
  TriangleMesh mesh = ExtrudePolygon(outline, cap, -0.5 * thickness, 0.5 * thickness);
  mesh.name = "l_rod";
  return mesh;
}

TriangleMesh MakeSpoon(const SpoonDimensions& d) {
  Require(Positive(d.length) && Positive(d.handle_width) && Positive(d.bowl_length) &&
              Positive(d.bowl_width) && Positive(d.bowl_depth) && Positive(d.thickness),
          "MakeSpoon: all dimensions must be finite and > 0");
  Require(d.bowl_length < d.length, "MakeSpoon: need bowl_length < length");
  Require(d.bowl_width > d.handle_width, "MakeSpoon: need bowl_width > handle_width");
  Require(d.segments_along >= 4 && d.segments_across >= 2,
          "MakeSpoon: need segments_along >= 4 and segments_across >= 2");
  const double a = 0.5 * d.bowl_length, b = 0.5 * d.bowl_width;
  const double x_c = d.length - a;  // bowl centre
  const double hw_handle = 0.5 * d.handle_width;
  // Where the bowl outline overtakes the handle, and where the tip is cut
  // (at a quarter of the bowl's half width, so the tip column is not degenerate).
  const double x_join = x_c - a * std::sqrt(1.0 - (hw_handle / b) * (hw_handle / b));
  const double x_tip = x_c + a * std::sqrt(1.0 - 0.25 * 0.25);
  auto half_width = [&](double x) {
    const double u = (x - x_c) / a;
    const double bowl = std::abs(u) < 1.0 ? b * std::sqrt(1.0 - u * u) : 0.0;
    return x <= x_c ? std::max(hw_handle, bowl) : bowl;
  };
  // The bowl's dip, inside a slightly smaller ellipse so a lip remains.
  auto dip = [&](double x, double y) {
    const double u = (x - x_c) / (0.85 * a), w = y / (0.85 * b);
    return -d.bowl_depth * std::max(0.0, 1.0 - u * u - w * w);
  };
  // Columns: handle end, mid-handle, then the bowl sampled evenly in angle.
  std::vector<double> xs = {0.0, 0.5 * x_join};
  const double t0 = std::acos(std::clamp((x_join - x_c) / a, -1.0, 1.0));
  const double t1 = std::acos(std::clamp((x_tip - x_c) / a, -1.0, 1.0));
  for (int i = 0; i <= d.segments_along; ++i) {
    const double t = t0 + (t1 - t0) * i / d.segments_along;
    xs.push_back(x_c + a * std::cos(t));
  }
  const int nx = static_cast<int>(xs.size()), ny = d.segments_across + 1;
  TriangleMesh mesh;
  mesh.name = "spoon";
  // Grid vertex (i, j) on the bottom face is i * ny + j, on the top face
  // nx * ny + i * ny + j.
  for (double z : {-0.5 * d.thickness, 0.5 * d.thickness}) {
    for (int i = 0; i < nx; ++i) {
      const double hw = half_width(xs[i]);
      for (int j = 0; j < ny; ++j) {
        const double y = hw * (2.0 * j / (ny - 1) - 1.0);
        mesh.vertices.emplace_back(xs[i], y, z + dip(xs[i], y));
      }
    }
  }
  const int top = nx * ny;
  auto g = [ny](int i, int j) { return i * ny + j; };
  for (int i = 0; i + 1 < nx; ++i) {
    for (int j = 0; j + 1 < ny; ++j) {
      AddQuad(&mesh, top + g(i, j), top + g(i + 1, j), top + g(i + 1, j + 1), top + g(i, j + 1));
      AddQuad(&mesh, g(i, j), g(i, j + 1), g(i + 1, j + 1), g(i + 1, j));
    }
  }
  // Side wall along the grid's boundary, walked counter-clockwise from +z.
  std::vector<int> loop;
  for (int i = 0; i < nx - 1; ++i) loop.push_back(g(i, 0));
  for (int j = 0; j < ny - 1; ++j) loop.push_back(g(nx - 1, j));
  for (int i = nx - 1; i > 0; --i) loop.push_back(g(i, ny - 1));
  for (int j = ny - 1; j > 0; --j) loop.push_back(g(0, j));
  const int m = static_cast<int>(loop.size());
  for (int k = 0; k < m; ++k) {
    const int u = loop[k], w = loop[(k + 1) % m];
    AddQuad(&mesh, u, w, top + w, top + u);
  }
  return mesh;
}

}  // namespace pd
