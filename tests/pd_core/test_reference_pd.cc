// Tests of the slow reference PD against cases with known answers, and of its
// collision test against FCL.
#include "pd_core/reference/reference_pd.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "pd_core/geometry/make_shapes.h"

namespace pd {
namespace {

Isometry3 At(double x, double y, double z) {
  Isometry3 X = Isometry3::Identity();
  X.translation() = Vector3(x, y, z);
  return X;
}

Isometry3 RandomPose(std::mt19937* rng, double spread) {
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uni(-spread, spread);
  return MakePose(Vector3(uni(*rng), uni(*rng), uni(*rng)), gauss(*rng), gauss(*rng),
                  gauss(*rng), gauss(*rng));
}

// Meshes side by side in one mesh (components stay separate).
TriangleMesh Union(const TriangleMesh& a, const Vector3& p_a, const TriangleMesh& b,
                   const Vector3& p_b) {
  TriangleMesh m;
  for (const Vector3& v : a.vertices) m.vertices.push_back(v + p_a);
  for (const Vector3& v : b.vertices) m.vertices.push_back(v + p_b);
  m.triangles = a.triangles;
  const int n = a.num_vertices();
  for (const auto& t : b.triangles) m.triangles.emplace_back(t + Eigen::Vector3i::Constant(n));
  return m;
}

// Open square of zero thickness in the plane x = 0: y in [y0, y1], z in [z0, z1].
TriangleMesh Quad(double y0, double y1, double z0, double z1) {
  TriangleMesh m;
  m.vertices = {{0, y0, z0}, {0, y1, z0}, {0, y1, z1}, {0, y0, z1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
Vector3 ClosestOnTriangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c) {
  const Vector3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Distance between segments p1-q1 and p2-q2 (Ericson, 5.1.9).
double SegmentDistance(const Vector3& p1, const Vector3& q1, const Vector3& p2,
                       const Vector3& q2) {
  const Vector3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= 0.0 && e <= 0.0) return r.norm();
  if (a <= 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom != 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p1 + s * d1 - (p2 + t * d2)).norm();
}

// Distance between triangles that do not cross: the nearest pair is a vertex
// and a triangle or two edges.
double TriangleDistance(const Vector3* a, const Vector3* b) {
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    d = std::min(d, (a[i] - ClosestOnTriangle(a[i], b[0], b[1], b[2])).norm());
    d = std::min(d, (b[i] - ClosestOnTriangle(b[i], a[0], a[1], a[2])).norm());
    for (int j = 0; j < 3; ++j) {
      d = std::min(d, SegmentDistance(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]));
    }
  }
  return d;
}

TriangleMesh SingleTriangle(const Vector3& a, const Vector3& b, const Vector3& c) {
  TriangleMesh m;
  m.vertices = {a, b, c};
  m.triangles = {{0, 1, 2}};
  return m;
}

std::vector<Vector3> WorldVertices(const TriangleMesh& m, const Isometry3& X_WM) {
  std::vector<Vector3> p;
  for (const Vector3& v : m.vertices) p.push_back(X_WM * v);
  return p;
}

// Unique edge vectors of a mesh with world vertices p.
std::vector<Vector3> EdgeVectors(const TriangleMesh& m, const std::vector<Vector3>& p) {
  std::map<std::pair<int, int>, Vector3> unique;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto key = std::minmax(t[k], t[(k + 1) % 3]);
      unique[key] = p[key.second] - p[key.first];
    }
  }
  std::vector<Vector3> e;
  for (const auto& [key, d] : unique) e.push_back(d);
  return e;
}

// For convex polytopes A and B in world: H(n) = max_B n·x - min_A n·x over the
// unit candidate normals n of the Minkowski difference B - A (face normals of
// both, edge-edge cross products, both signs). A moved by t meets B iff
// n·t <= H(n) for all n.
struct MinkowskiFacets {
  std::vector<Vector3> n;
  std::vector<double> h;
};

MinkowskiFacets Facets(const TriangleMesh& a, const Isometry3& X_WA, const TriangleMesh& b,
                       const Isometry3& X_WB) {
  const std::vector<Vector3> pa = WorldVertices(a, X_WA), pb = WorldVertices(b, X_WB);
  std::vector<Vector3> axes;
  for (const auto* m : {&a, &b}) {
    const auto& p = m == &a ? pa : pb;
    for (const auto& t : m->triangles) axes.push_back((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]));
  }
  for (const Vector3& ea : EdgeVectors(a, pa)) {
    for (const Vector3& eb : EdgeVectors(b, pb)) axes.push_back(ea.cross(eb));
  }
  MinkowskiFacets f;
  for (const Vector3& axis : axes) {
    if (axis.norm() < 1e-12) continue;
    for (const Vector3& n : {Vector3(axis.normalized()), Vector3(-axis.normalized())}) {
      double a_lo = 1e300, b_hi = -1e300;
      for (const Vector3& p : pa) a_lo = std::min(a_lo, n.dot(p));
      for (const Vector3& p : pb) b_hi = std::max(b_hi, n.dot(p));
      f.n.push_back(n);
      f.h.push_back(b_hi - a_lo);
    }
  }
  return f;
}

// Exact PD of two convex polytopes by the separating-axis theorem: the
// smallest H(n), reached moving A along n.
double SatDepth(const TriangleMesh& a, const Isometry3& X_WA, const TriangleMesh& b,
                const Isometry3& X_WB, Vector3* direction_W) {
  const MinkowskiFacets f = Facets(a, X_WA, b, X_WB);
  const auto it = std::min_element(f.h.begin(), f.h.end());
  *direction_W = f.n[it - f.h.begin()];
  return *it;
}

// Exact exit of convex A along unit u (A colliding with B at t = 0): where the
// ray s u leaves B - A, min over n·u > 0 of H(n) / n·u.
double ConvexExit(const MinkowskiFacets& f, const Vector3& u) {
  double exit = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < f.n.size(); ++i) {
    const double c = f.n[i].dot(u);
    if (c > 1e-12) exit = std::min(exit, f.h[i] / c);
  }
  return exit;
}

// Expected PD of axis-aligned boxes: the smallest of the six axis overlaps.
double AxisAlignedBoxDepth(const Vector3& half_p, const Vector3& p_WP, const Vector3& half_s,
                           const Vector3& p_WS) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, (p_WS[i] + half_s[i]) - (p_WP[i] - half_p[i]));
    best = std::min(best, (p_WP[i] + half_p[i]) - (p_WS[i] - half_s[i]));
  }
  return best;
}

const std::vector<Vector3> kAxes = {Vector3::UnitX(),  Vector3::UnitY(),  Vector3::UnitZ(),
                                    -Vector3::UnitX(), -Vector3::UnitY(), -Vector3::UnitZ()};

TEST(ReferencePdTest, NotCollidingGivesZero) {
  const TriangleMesh box = MakeBox(Vector3(0.5, 0.5, 0.5));
  const Isometry3 X_WP = At(1.2, 0.3, 0.0), X_WS = At(0, 0, 0);
  EXPECT_FALSE(ReferenceInCollision(box, X_WP, true, box, X_WS, true));
  const ReferencePdResult r = ReferencePenetrationDepth(box, X_WP, true, box, X_WS, true);
  EXPECT_FALSE(r.in_collision);
  EXPECT_EQ(r.depth, 0.0);
  EXPECT_EQ(r.translation_W, Vector3::Zero());
  EXPECT_EQ(DirectionalPenetration(box, X_WP, true, box, X_WS, true, -Vector3::UnitX(), 1e-6),
            0.0);
}

// Exit along the axes equals the overlaps exactly. The search reaches the
// minimum through the contact normals without help (asserted to 1e-9
// relative; it is exact in practice), and with the axes among the evaluated
// directions it needs no refinement at all (1e-12).
TEST(ReferencePdTest, AxisAlignedBoxes) {
  struct Case {
    Vector3 half_p, p_WP, half_s, p_WS;
  };
  const std::vector<Case> cases = {
      {{0.5, 0.5, 0.5}, {0, 0, 0}, {1, 1, 1}, {1.2, 0.1, 0}},       // shallow in x
      {{0.5, 0.3, 0.2}, {0.1, 0.2, 0.9}, {1, 1, 1}, {0, 0, 0}},     // through the top
      {{1, 1, 1}, {0.3, -0.2, 0.1}, {0.9, 0.8, 0.95}, {0, 0, 0}},   // nearly coincident
      {{0.2, 2.0, 0.2}, {0, 0, 0}, {1, 0.1, 1}, {0.5, 0.2, 0.6}},   // crossing bars
  };
  ReferencePdOptions options;
  options.num_directions = 1000;
  ReferencePdOptions with_axes = options;
  with_axes.extra_directions_W = kAxes;  // the Fibonacci set has no exact axes
  for (const Case& c : cases) {
    const TriangleMesh probe = MakeBox(c.half_p), scene = MakeBox(c.half_s);
    const Isometry3 X_WP = At(c.p_WP.x(), c.p_WP.y(), c.p_WP.z());
    const Isometry3 X_WS = At(c.p_WS.x(), c.p_WS.y(), c.p_WS.z());
    const double expected = AxisAlignedBoxDepth(c.half_p, c.p_WP, c.half_s, c.p_WS);
    ASSERT_GT(expected, 0.0);
    for (int i = 0; i < 3; ++i) {
      const double plus = (c.p_WS[i] + c.half_s[i]) - (c.p_WP[i] - c.half_p[i]);
      const double minus = (c.p_WP[i] + c.half_p[i]) - (c.p_WS[i] - c.half_s[i]);
      EXPECT_NEAR(DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, kAxes[i], 1e-9),
                  plus, 1e-12);
      EXPECT_NEAR(
          DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, kAxes[i + 3], 1e-9),
          minus, 1e-12);
    }
    const ReferencePdResult r = ReferencePenetrationDepth(probe, X_WP, true, scene, X_WS, true,
                                                          options);
    EXPECT_TRUE(r.in_collision);
    EXPECT_GE(r.depth, expected - 1e-12);
    EXPECT_NEAR(r.depth, expected, 1e-9 * expected);
    EXPECT_NEAR(r.translation_W.norm(), r.depth, 1e-12);
    ReferencePdOptions no_refinement = with_axes;
    no_refinement.refine_iterations = 0;
    const ReferencePdResult exact = ReferencePenetrationDepth(probe, X_WP, true, scene, X_WS,
                                                              true, no_refinement);
    EXPECT_NEAR(exact.depth, expected, 1e-12);
  }
}

// Convex pairs in general position: the answer of the separating-axis theorem
// (to 1e-9 relative; the contact-normal refinement makes it exact in practice).
TEST(ReferencePdTest, ConvexPairsMatchSeparatingAxes) {
  std::mt19937 rng(7);
  const std::vector<std::pair<TriangleMesh, TriangleMesh>> pairs = {
      {MakeBox(Vector3(0.4, 0.25, 0.15)), MakeBox(Vector3(0.5, 0.5, 0.5))},
      {MakeIcosphere(0.4, 0), MakeBox(Vector3(0.3, 0.6, 0.2))},
      {MakeBox(Vector3(0.2, 0.3, 0.5)), MakeIcosphere(0.5, 0)},
  };
  ReferencePdOptions options;
  options.num_directions = 1000;
  int checked = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const auto& [probe, scene] = pairs[trial % pairs.size()];
    // The first trial is a rotated probe against an axis-aligned box.
    const Isometry3 X_WS = trial == 0 ? At(0, 0, 0) : RandomPose(&rng, 0.1);
    const Isometry3 X_WP = RandomPose(&rng, 0.4);
    Vector3 n_W;
    const double expected = SatDepth(probe, X_WP, scene, X_WS, &n_W);
    if (expected <= 1e-3) continue;  // not (clearly) colliding
    ++checked;
    const ReferencePdResult r = ReferencePenetrationDepth(probe, X_WP, true, scene, X_WS, true,
                                                          options);
    ASSERT_TRUE(r.in_collision);
    EXPECT_GE(r.depth, expected - 1e-9) << "trial " << trial;
    EXPECT_NEAR(r.depth, expected, 1e-9 * expected) << "trial " << trial;
    // Along the separating-axis normal the exit is exact.
    EXPECT_NEAR(DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, n_W, 0.0), expected,
                1e-9)
        << "trial " << trial;
  }
  EXPECT_GE(checked, 6);
}

// Convex pairs along directions that make triangles parallel to u and edges
// project to points (face normals, edge directions), where the interval
// events degenerate, against the exit of the Minkowski-difference facets.
TEST(ReferencePdTest, DirectionalExitOfConvexPairsInDegenerateDirections) {
  std::mt19937 rng(17);
  std::normal_distribution<double> gauss;
  const std::vector<std::pair<TriangleMesh, TriangleMesh>> pairs = {
      {MakeBox(Vector3(0.4, 0.25, 0.15)), MakeBox(Vector3(0.5, 0.5, 0.5))},
      {MakeIcosphere(0.4, 0), MakeBox(Vector3(0.3, 0.6, 0.2))},
      {MakeBox(Vector3(0.2, 0.3, 0.5)), MakeIcosphere(0.5, 0)},
  };
  int checked = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const auto& [probe, scene] = pairs[trial % pairs.size()];
    // Every third pose is axis-aligned, where many directions are exact axes.
    const bool aligned = trial % 3 == 0;
    const Isometry3 X_WS = aligned ? At(0, 0, 0) : RandomPose(&rng, 0.1);
    const Isometry3 X_WP = aligned ? At(0.1 * gauss(rng), 0.1 * gauss(rng), 0.1 * gauss(rng))
                                   : RandomPose(&rng, 0.3);
    const MinkowskiFacets facets = Facets(probe, X_WP, scene, X_WS);
    if (*std::min_element(facets.h.begin(), facets.h.end()) <= 1e-3) continue;
    std::vector<Vector3> dirs;
    for (const auto& [m, X] : {std::make_pair(&probe, X_WP), std::make_pair(&scene, X_WS)}) {
      const std::vector<Vector3> p = WorldVertices(*m, X);
      for (const auto& t : m->triangles) {
        dirs.push_back((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).normalized());
      }
      for (const Vector3& e : EdgeVectors(*m, p)) dirs.push_back(e.normalized());
    }
    for (int i = 0; i < 10; ++i) dirs.emplace_back(gauss(rng), gauss(rng), gauss(rng));
    for (Vector3 u : dirs) {
      for (const Vector3& v : {Vector3(u.normalized()), Vector3(-u.normalized())}) {
        ++checked;
        EXPECT_NEAR(DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, v, 0.0),
                    ConvexExit(facets, v), 1e-9)
            << "trial " << trial << " u " << v.transpose();
      }
    }
  }
  EXPECT_GT(checked, 500);
}

// Icospheres lie inside their spheres and contain the spheres of their
// inscribed radius, so r_in1 + r_in2 - d <= PD <= r1 + r2 - d; being convex,
// the separating axes give the exact value.
TEST(ReferencePdTest, Icospheres) {
  const double r1 = 0.5, r2 = 0.7, d = 0.9;
  const TriangleMesh probe = MakeIcosphere(r1, 2), scene = MakeIcosphere(r2, 2);
  const Vector3 axis = Vector3(0.3, -0.5, 0.8).normalized();
  const Isometry3 X_WP = MakePose(d * axis, 0.9, 0.1, 0.3, -0.2);
  const Isometry3 X_WS = MakePose(Vector3::Zero(), 0.2, -0.7, 0.1, 0.4);
  auto inscribed = [](const TriangleMesh& m) {
    double r = 1e300;
    for (int t = 0; t < m.num_triangles(); ++t) {
      r = std::min(r, FaceNormal(m, t).dot(m.vertices[m.triangles[t][0]]));
    }
    return r;
  };
  ReferencePdOptions options;
  options.num_directions = 500;
  const ReferencePdResult r = ReferencePenetrationDepth(probe, X_WP, true, scene, X_WS, true,
                                                        options);
  ASSERT_TRUE(r.in_collision);
  EXPECT_LE(r.depth, r1 + r2 - d + 1e-9);
  EXPECT_GE(r.depth, inscribed(probe) + inscribed(scene) - d - 1e-9);
  Vector3 n_W;
  const double exact = SatDepth(probe, X_WP, scene, X_WS, &n_W);
  EXPECT_NEAR(r.depth, exact, 1e-9 * exact);
  EXPECT_GT(r.direction_W.dot(axis), 0.99);
}

// Probe inside a closed box: it must leave through the nearest face, so the
// depth is that face's distance plus the probe's extent toward it.
TEST(ReferencePdTest, ProbeInsideClosedBox) {
  const TriangleMesh scene = MakeBox(Vector3(1, 1, 1));
  const TriangleMesh probe = MakeBox(Vector3(0.1, 0.2, 0.1));
  const Isometry3 X_WP = At(0.6, 0.0, 0.1), X_WS = At(0, 0, 0);
  const double expected = (1.0 - 0.6) + 0.1;  // through +x
  ReferencePdOptions options;
  options.num_directions = 1000;
  options.extra_directions_W = kAxes;
  EXPECT_TRUE(ReferenceInCollision(probe, X_WP, true, scene, X_WS, true));
  const ReferencePdResult r = ReferencePenetrationDepth(probe, X_WP, true, scene, X_WS, true,
                                                        options);
  EXPECT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, expected, 1e-12);
  EXPECT_NEAR(r.direction_W.x(), 1.0, 1e-12);
  EXPECT_NEAR(DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, Vector3::UnitZ(), 1e-6),
              (1.0 - 0.1) + 0.1, 1e-12);
  EXPECT_NEAR(
      DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, -Vector3::UnitY(), 1e-6),
      1.0 + 0.2, 1e-12);
  // As a shell (open), the scene does not hold the probe.
  EXPECT_FALSE(ReferenceInCollision(probe, X_WP, true, scene, X_WS, false));
  EXPECT_FALSE(ReferencePenetrationDepth(probe, X_WP, true, scene, X_WS, false, options)
                   .in_collision);
}

// The mirror case: the probe must move until the scene is outside it.
TEST(ReferencePdTest, SceneInsideProbe) {
  const TriangleMesh probe = MakeBox(Vector3(1, 1, 1));
  const TriangleMesh scene = MakeBox(Vector3(0.1, 0.2, 0.1));
  const Isometry3 X_WP = At(0, 0, 0), X_WS = At(0.6, 0.0, 0.1);
  ReferencePdOptions options;
  options.num_directions = 1000;
  const ReferencePdResult r = ReferencePenetrationDepth(probe, X_WP, true, scene, X_WS, true,
                                                        options);
  EXPECT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, 0.5, 1e-9 * 0.5);
  EXPECT_GT(-r.direction_W.x(), 0.999);
  EXPECT_NEAR(
      DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, -Vector3::UnitX(), 1e-6), 0.5,
      1e-12);
  EXPECT_FALSE(ReferenceInCollision(probe, X_WP, false, scene, X_WS, true));
}

// A peg wedged between thin walls of a U slot, touching the floor: pushing it
// out of a wall (0.02) or the floor (0.05) is not enough, it must rise above
// the walls (0.45); sideways out of the whole U is 0.57, along the slot 2.3.
TEST(ReferencePdTest, PegInUSlotLeavesThroughTheOpening) {
  // Walls y in [0.25, 0.3] (and mirrored), floor z = 0.1, top z = 0.5.
  const TriangleMesh slot = MakeUSlot(Vector3(2.0, 0.3, 0.5), 0.5, 0.4);
  const TriangleMesh peg = MakeBox(Vector3(0.3, 0.27, 0.2));
  const Isometry3 X_WP = At(0, 0, 0.25), X_WS = At(0, 0, 0);
  ReferencePdOptions options;
  options.num_directions = 2000;
  const ReferencePdResult r = ReferencePenetrationDepth(peg, X_WP, true, slot, X_WS, true,
                                                        options);
  ASSERT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, 0.45, 1e-9 * 0.45);
  EXPECT_GT(r.direction_W.z(), 0.999);
  const double up =
      DirectionalPenetration(peg, X_WP, true, slot, X_WS, true, Vector3::UnitZ(), 1e-6);
  const double side =
      DirectionalPenetration(peg, X_WP, true, slot, X_WS, true, Vector3::UnitY(), 1e-6);
  const double along =
      DirectionalPenetration(peg, X_WP, true, slot, X_WS, true, Vector3::UnitX(), 1e-6);
  EXPECT_NEAR(up, 0.45, 1e-12);
  EXPECT_NEAR(side, 0.57, 1e-12);
  EXPECT_NEAR(along, 2.3, 1e-12);
}

// A cube pushed into an inner corner of a slot (its floor and one wall):
// it must move off both at once, so the PD lies on the crease of two
// C-obstacle planes, t = (0, -d_wall, d_floor), where the directional exit is
// a V-shaped valley that a pattern search along fixed axes zig-zags down.
// The refinement's plane model lands on the crease with few directions and a
// small budget.
TEST(ReferencePdTest, CubeInSlotCornerRefinesOntoTheCrease) {
  // Slot walls at |y| >= 0.5, floor z = 0, top z = 1.
  const TriangleMesh slot = MakeUSlot(Vector3(1.0, 1.0, 1.0), 1.0, 1.0);
  const TriangleMesh cube = MakeBox(Vector3(0.2, 0.2, 0.2));
  const double d_floor = 0.03, d_wall = 0.05;
  const Isometry3 X_WP = At(0, 0.5 - 0.2 + d_wall, 0.2 - d_floor), X_WS = At(0, 0, 0);
  ReferencePdOptions options;
  options.num_directions = 64;
  options.refine_iterations = 24;
  const ReferencePdResult r = ReferencePenetrationDepth(cube, X_WP, true, slot, X_WS, true,
                                                        options);
  ASSERT_TRUE(r.in_collision);
  const double exact = std::hypot(d_floor, d_wall);
  EXPECT_NEAR(r.depth, exact, 1e-9 * exact);
  EXPECT_NEAR(r.translation_W.y(), -d_wall, 1e-9);
  EXPECT_NEAR(r.translation_W.z(), d_floor, 1e-9);
  // The reference's answer is free (its own test), and the crease point is
  // the shortest: each axis alone leaves the cube in the other wall.
  EXPECT_FALSE(ReferenceInCollision(cube, X_WP, true, slot, X_WS, true,
                                    r.translation_W * (1.0 + 1e-9)));
  EXPECT_TRUE(ReferenceInCollision(cube, X_WP, true, slot, X_WS, true,
                                   Vector3(0, -d_wall * 1.01, 0)));
  EXPECT_TRUE(ReferenceInCollision(cube, X_WP, true, slot, X_WS, true,
                                   Vector3(0, 0, d_floor * 1.01)));
}

// A zero-thickness plate stuck in the top of one of two boxes separated by a
// slit of 1e-6 m: slipping into the slit (5e-7 m away, or further at an angle)
// is free only inside a slit thinner than slit_tol * size (about 3e-6 m), so
// the plate must rise out (0.5 m). With a tiny slit_tol the slit counts.
TEST(ReferencePdTest, SlitThinnerThanToleranceIsNoEscape) {
  const double gap = 1e-6;
  const TriangleMesh block = MakeBox(Vector3(1, 1, 1));
  const TriangleMesh scene =
      Union(block, Vector3(-1 - gap / 2, 0, 0), block, Vector3(1 + gap / 2, 0, 0));
  const TriangleMesh plate = Quad(-0.5, 0.5, 0.5, 1.5);
  const Isometry3 X_WP = At(gap, 0, 0), X_WS = At(0, 0, 0);
  ReferencePdOptions options;
  options.num_directions = 1000;
  options.extra_directions_W = kAxes;
  const ReferencePdResult r = ReferencePenetrationDepth(plate, X_WP, false, scene, X_WS, true,
                                                        options);
  ASSERT_TRUE(r.in_collision);
  EXPECT_NEAR(r.depth, 0.5, 1e-12);
  EXPECT_NEAR(r.direction_W.z(), 1.0, 1e-12);
  const double size_slit_tol = 1e-6 * 3.0;  // size is about 3.2 m
  EXPECT_NEAR(DirectionalPenetration(plate, X_WP, false, scene, X_WS, true, -Vector3::UnitX(),
                                     size_slit_tol),
              2.0 + 1.5 * gap, 1e-12);  // out of the far side of the other box
  EXPECT_NEAR(DirectionalPenetration(plate, X_WP, false, scene, X_WS, true, -Vector3::UnitX(),
                                     1e-9),
              gap / 2, 1e-15);
  options.slit_tol = 1e-9;
  const ReferencePdResult fine = ReferencePenetrationDepth(plate, X_WP, false, scene, X_WS, true,
                                                           options);
  EXPECT_NEAR(fine.depth, gap / 2, 1e-15);
  EXPECT_NEAR(fine.direction_W.x(), -1.0, 1e-12);
}

// Single triangle pairs, many of them degenerate (grid coordinates, axis and
// diagonal directions): the exit along u ends the touching interval, so the
// pair touches just before it and not just after. Grid pairs often only graze
// (a vertex sliding along an edge), where a floating-point collision test
// may go either way, so "touches" means colliding or closer than 1e-12 m.
TEST(ReferencePdTest, DirectionalExitBracketsContactOfTrianglePairs) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> grid(0, 2);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const std::vector<Vector3> grid_dirs = {
      Vector3(1, 0, 0),  Vector3(0, -1, 0), Vector3(0, 0, 1),  Vector3(1, 1, 0).normalized(),
      Vector3(0, -1, 1).normalized(), Vector3(1, 1, 1).normalized(),
      Vector3(-1, 2, 0).normalized()};
  const double delta = 1e-7;
  int colliding = 0, checked_exits = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const bool on_grid = trial % 2 == 0;
    auto point = [&]() {
      return on_grid ? Vector3(grid(rng), grid(rng), grid(rng)) * 0.5
                     : Vector3(uni(rng), uni(rng), uni(rng));
    };
    const TriangleMesh a = SingleTriangle(point(), point(), point());
    const TriangleMesh b = SingleTriangle(point(), point(), point());
    if ((a.vertices[1] - a.vertices[0]).cross(a.vertices[2] - a.vertices[0]).norm() < 1e-9 ||
        (b.vertices[1] - b.vertices[0]).cross(b.vertices[2] - b.vertices[0]).norm() < 1e-9) {
      continue;  // degenerate triangles only count through their edges
    }
    const Vector3 u = on_grid ? grid_dirs[trial % grid_dirs.size()]
                              : Vector3(uni(rng), uni(rng), uni(rng)).normalized();
    const Isometry3 I = Isometry3::Identity();
    const bool hit = ReferenceInCollision(a, I, false, b, I, false);
    const double exit = DirectionalPenetration(a, I, false, b, I, false, u, 0.0);
    if (!hit) {
      EXPECT_EQ(exit, 0.0) << "trial " << trial;
      continue;
    }
    ++colliding;
    if (exit < 10 * delta) continue;  // touching only at the start
    ++checked_exits;
    const Vector3 before[3] = {a.vertices[0] + (exit - delta) * u,
                               a.vertices[1] + (exit - delta) * u,
                               a.vertices[2] + (exit - delta) * u};
    EXPECT_TRUE(ReferenceInCollision(a, I, false, b, I, false, (exit - delta) * u) ||
                TriangleDistance(before, b.vertices.data()) < 1e-12)
        << "trial " << trial;
    EXPECT_FALSE(ReferenceInCollision(a, I, false, b, I, false, (exit + delta) * u))
        << "trial " << trial;
  }
  EXPECT_GT(colliding, 300);
  EXPECT_GT(checked_exits, 200);
}

// Non-convex closed meshes in random poses: P collides all along [0, exit]
// (sampled) and is free just after it.
TEST(ReferencePdTest, DirectionalExitAgreesWithCollisionMarch) {
  const TriangleMesh probe = MakeTorus(0.3, 0.08, 16, 8);
  const TriangleMesh scene = MakeTorusKnot(2, 3, 0.08, 0.4, 64, 6);
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss;
  int checked = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const Isometry3 X_WP = RandomPose(&rng, 0.3), X_WS = RandomPose(&rng, 0.0);
    if (!ReferenceInCollision(probe, X_WP, true, scene, X_WS, true)) continue;
    for (int k = 0; k < 4; ++k) {
      const Vector3 u = Vector3(gauss(rng), gauss(rng), gauss(rng)).normalized();
      const double exit =
          DirectionalPenetration(probe, X_WP, true, scene, X_WS, true, u, 1e-6);
      ASSERT_GT(exit, 0.0);
      ++checked;
      EXPECT_FALSE(ReferenceInCollision(probe, X_WP, true, scene, X_WS, true, (exit + 1e-9) * u))
          << "trial " << trial;
      for (int i = 0; i <= 16; ++i) {
        const double s = std::min(i / 16.0, 1.0 - 1e-9) * exit;
        EXPECT_TRUE(ReferenceInCollision(probe, X_WP, true, scene, X_WS, true, s * u))
            << "trial " << trial << " s " << s << " exit " << exit;
      }
    }
  }
  EXPECT_GT(checked, 20);
}

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> ToFcl(const TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> vertices(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel();
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}

// FCL's mesh collide tests surfaces only, so compare with open meshes; with
// closed meshes the only extra collisions are containments.
TEST(ReferencePdTest, InCollisionAgreesWithFcl) {
  const TriangleMesh probe = MakeIcosphere(0.3, 1);
  const TriangleMesh scene = MakeTorus(0.5, 0.2, 24, 12);
  const auto probe_fcl = ToFcl(probe), scene_fcl = ToFcl(scene);
  std::mt19937 rng(11);
  int hits = 0, misses = 0, contained = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Isometry3 X_WP = RandomPose(&rng, 0.8), X_WS = RandomPose(&rng, 0.1);
    fcl::CollisionObjectd probe_obj(probe_fcl, X_WP), scene_obj(scene_fcl, X_WS);
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    fcl::collide(&probe_obj, &scene_obj, request, result);
    const bool surface = ReferenceInCollision(probe, X_WP, false, scene, X_WS, false);
    EXPECT_EQ(surface, result.isCollision()) << "trial " << trial;
    const bool solid = ReferenceInCollision(probe, X_WP, true, scene, X_WS, true);
    if (surface) {
      EXPECT_TRUE(solid);
    }
    if (solid && !surface) {
      ++contained;
      // Contained without touching: the probe's centre is inside the torus.
      const Vector3 p_SP = X_WS.inverse() * X_WP.translation();
      EXPECT_LT(std::hypot(std::hypot(p_SP.x(), p_SP.y()) - 0.5, p_SP.z()), 0.2);
    }
    (surface ? hits : misses)++;
  }
  EXPECT_GT(hits, 40);
  EXPECT_GT(misses, 40);
}

}  // namespace
}  // namespace pd
