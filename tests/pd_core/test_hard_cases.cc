// Hard geometric cases for PolyDepth (issue 5): touching, coplanar faces,
// parallel edges, deep penetration, identical meshes at one pose, highly
// tessellated against coarse models, tiny and huge scales, slivers and
// duplicate vertices, open meshes and polygon soups, needles. Every answer
// must be finite and verified collision-free (independently, by the
// reference code), its iteration count bounded, and its depth within a
// stated tolerance above the slow reference PD (pd_core/reference/reference_pd.h),
// which gets no hint from the solver; where the case has an analytic PD, the
// answer is checked against it too. Both answers are upper bounds on the true
// PD (verified free), so ours below the reference means the reference
// stopped short, not that ours is wrong. Tolerances are relative to the
// depth or to the pair's size, never absolute lengths. Cases that test_polydepth.cc already covers
// (probe or scene wholly inside the other, coherent push through a thin
// plate, 1e-3 scale) are not repeated here.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/reference/reference_pd.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;

const Isometry3 kIdentity = Isometry3::Identity();

Isometry3 At(const Vector3& p_WA, const Quaternion& q_WA = Quaternion::Identity()) {
  return MakePose(p_WA, q_WA.w(), q_WA.x(), q_WA.y(), q_WA.z());
}

Quaternion AboutX(double angle) { return Quaternion(Eigen::AngleAxisd(angle, Vector3::UnitX())); }

// The most projection iterations one query may take: every start that is
// iterated (two coherence attempts, the cold starts, the 4 free shell
// probes, the 2 inner probes, the sampling fallback) runs at most
// max_iterations, the cold polish one step.
int IterationBound(const PolyDepthOptions& o) {
  return o.max_iterations * (o.num_iterated_starts + 9) + 1;
}

double PairSize(const Model& P, const Model& S) { return P->radius() + S->radius(); }

struct Checked {
  PenetrationResult fast;
  ReferencePdResult ref;
};

// Absolute slack on depths: answers are backed off by the solver's
// separation margin (a fraction of the pair's size) to be strictly free and
// polished to within a few margins (measured: up to 3.1 at touching).
double Slack(const Model& P, const Model& S, const PolyDepthOptions& o = {}) {
  return 5.0 * o.separation_margin * PairSize(P, S);
}

// Solves cold and checks what every hard case must satisfy: collision state
// agrees with the reference, answer finite, bounded iterations, verified
// free by both the solver and the independent reference test (so depth >=
// the true PD), and depth <= ref * (1 + rel_tol) + slack.
Checked SolveAndCheck(const Model& P, const Isometry3& X_WP, const Model& S, const Isometry3& X_WS,
                      double rel_tol, const std::string& label, int num_directions = 600) {
  PolyDepthSolver solver(P, S);
  Checked c;
  c.fast = solver.Solve(X_WP, X_WS);
  const PenetrationResult& r = c.fast;
  EXPECT_TRUE(std::isfinite(r.depth) && r.translation_W.allFinite() && r.normal_W.allFinite())
      << label;
  EXPECT_LE(r.iterations, IterationBound(solver.options())) << label;
  ReferencePdOptions ro;
  ro.num_directions = num_directions;
  c.ref = ReferencePenetrationDepth(P->mesh(), X_WP, P->closed(), S->mesh(), X_WS, S->closed(), ro);
  EXPECT_EQ(r.in_collision, c.ref.in_collision) << label;
  if (!r.in_collision) return c;
  EXPECT_TRUE(r.valid) << label;
  EXPECT_FALSE(ReferenceInCollision(P->mesh(), X_WP, P->closed(), S->mesh(), X_WS, S->closed(),
                                    r.translation_W))
      << label << ": the answer is not free";
  const double slack = Slack(P, S, solver.options());
  EXPECT_LE(r.depth, c.ref.depth * (1.0 + rel_tol) + slack)
      << label << ": depth " << r.depth << " reference " << c.ref.depth;
  std::printf("[ case     ] %-44s depth %.6g ref %.6g err %+.2e iterations %d %s\n", label.c_str(),
              r.depth, c.ref.depth, c.ref.depth > 0 ? (r.depth - c.ref.depth) / c.ref.depth : 0.0,
              r.iterations, InitializerName(r.initializer));
  return c;
}

TEST(HardCases, TouchingContactHasNearZeroDepth) {
  Model P = CollisionModel::Build(MakeBox(Vector3(0.1, 0.1, 0.1)));
  Model S = CollisionModel::Build(MakeBox(Vector3(1, 1, 1)));
  const double size = PairSize(P, S);
  // Resting exactly on the top face; then overlapping by 1e-9 and 1e-6 of size.
  for (double overlap : {0.0, 1e-9, 1e-6}) {
    const Isometry3 X_WP = At(Vector3(0.3, -0.2, 1.1 - overlap * size));
    const Checked c = SolveAndCheck(P, X_WP, S, kIdentity, 1e-6, "touching face, overlap " +
                                                                     std::to_string(overlap));
    EXPECT_LE(c.fast.depth, overlap * size + Slack(P, S));
    // Below the contact tolerance the escape direction is arbitrary (any
    // upward tilt frees the probe by about as little): not judged.
    if (c.fast.depth > PolyDepthOptions{}.contact_tol * size) EXPECT_GT(c.fast.normal_W.z(), 0.999);
  }
  // An edge of a tilted probe grazing the face.
  const Isometry3 X_WP = At(Vector3(0, 0, 1.0 + 0.1 * std::sqrt(2.0) - 1e-9 * size), AboutX(M_PI / 4));
  const Checked c = SolveAndCheck(P, X_WP, S, kIdentity, 1e-6, "touching edge on face");
  EXPECT_LE(c.fast.depth, 1e-9 * size + Slack(P, S));
}

TEST(HardCases, CoplanarFaceFaceContact) {
  // Identical boxes stacked with 0.1 overlap: the four side faces coplanar.
  Model P = CollisionModel::Build(MakeBox(Vector3(0.5, 0.5, 0.5)));
  Checked c = SolveAndCheck(P, At(Vector3(0, 0, 0.9)), P, kIdentity, 1e-6, "identical boxes stacked");
  EXPECT_NEAR(c.fast.depth, 0.1, 1e-6 * 0.1);
  EXPECT_GT(std::abs(c.fast.normal_W.z()), 0.999);
  // A smaller box in a corner of a bigger one's top: two side faces flush.
  Model S = CollisionModel::Build(MakeBox(Vector3(1, 1, 1)));
  c = SolveAndCheck(P, At(Vector3(0.5, 0.5, 1.4)), S, kIdentity, 1e-6, "corner-flush box on box");
  EXPECT_NEAR(c.fast.depth, 0.1, 1e-6 * 0.1);
  EXPECT_GT(c.fast.normal_W.z(), 0.999);
}

TEST(HardCases, ParallelEdgeEdgeContact) {
  // Both boxes turned 45 degrees about x: the probe's lowest edge and the
  // scene's highest edge are parallel (both along x) and overlap by d
  // vertically. The Minkowski difference has faces at 45 degrees there, so
  // PD = d / sqrt(2).
  const double hs = 0.5, hp = 0.2, d = 0.02;
  Model S = CollisionModel::Build(MakeBox(Vector3(hs, hs, hs)));
  Model P = CollisionModel::Build(MakeBox(Vector3(0.3, hp, hp)));
  const Isometry3 X_WS = At(Vector3::Zero(), AboutX(M_PI / 4));
  const Isometry3 X_WP = At(Vector3(0.1, 0, std::sqrt(2.0) * (hs + hp) - d), AboutX(M_PI / 4));
  const Checked c = SolveAndCheck(P, X_WP, S, X_WS, 1e-6, "parallel edges");
  EXPECT_NEAR(c.fast.depth, d / std::sqrt(2.0), 1e-6 * d);
}

TEST(HardCases, IdenticalMeshesAtTheSamePose) {
  // Box: leave along the shortest axis, both ways the same: 2 * 0.1.
  Model box = CollisionModel::Build(MakeBox(Vector3(0.3, 0.2, 0.1)));
  const Checked b = SolveAndCheck(box, kIdentity, box, kIdentity, 1e-6, "identical boxes");
  EXPECT_NEAR(b.fast.depth, 0.2, 1e-6 * 0.2);
  EXPECT_GT(std::abs(b.fast.normal_W.z()), 0.999);
  // Ball: out by its width across faces (convex: exact).
  Model ball = CollisionModel::Build(MakeIcosphere(0.2, 2));
  SolveAndCheck(ball, kIdentity, ball, kIdentity, 1e-4, "identical icospheres");
  // Non-convex: a knot on itself.
  Model knot = CollisionModel::Build(MakeTorusKnot(2, 3, 0.12, 0.5, 48, 6));
  SolveAndCheck(knot, kIdentity, knot, kIdentity, 0.05, "identical torus knots", 300);
}

TEST(HardCases, DeepPenetrationBeyondHalfTheProbe) {
  Model S = CollisionModel::Build(MakeBox(Vector3(1, 1, 1)));
  // 0.2 box whose bottom is 0.15 under the top face (half its size: 0.1).
  Model P = CollisionModel::Build(MakeBox(Vector3(0.1, 0.1, 0.1)));
  const Checked c = SolveAndCheck(P, At(Vector3(0.2, 0.3, 0.95)), S, kIdentity, 1e-6, "deep box");
  EXPECT_NEAR(c.fast.depth, 0.15, 1e-6 * 0.15);
  EXPECT_GT(c.fast.normal_W.z(), 0.999);
  // A turned ball 0.17 deep near a corner of the box.
  Model ball = CollisionModel::Build(MakeIcosphere(0.1, 2));
  SolveAndCheck(ball, At(Vector3(0.85, 0.7, 0.93), Quaternion(0.9, 0.1, 0.3, -0.2)), S, kIdentity,
                1e-3, "deep ball at a corner");
  // Non-convex scene: a ball sunk past its middle into a knot's tube.
  Model knot = CollisionModel::Build(MakeTorusKnot(2, 3, 0.2, 1.0, 96, 8));
  const Vector3 on_tube = knot->mesh().vertices[0];
  SolveAndCheck(ball, At(on_tube * 0.93), knot, kIdentity, 0.02, "ball deep in a knot tube", 300);
}

TEST(HardCases, HighlyTessellatedAgainstCoarse) {
  Model fine = CollisionModel::Build(MakeIcosphere(0.3, 5));  // 20480 triangles
  Model box = CollisionModel::Build(MakeBox(Vector3(1, 1, 1)));   // 12 triangles
  ASSERT_EQ(fine->mesh().num_triangles(), 20480);
  // The fine ball pressed into a face, an edge and a corner of the box.
  SolveAndCheck(fine, At(Vector3(0.2, -0.1, 1.25)), box, kIdentity, 1e-4, "fine ball on face", 300);
  SolveAndCheck(fine, At(Vector3(0.3, 1.15, 1.15)), box, kIdentity, 1e-3, "fine ball on edge", 300);
  SolveAndCheck(fine, At(Vector3(1.15, 1.15, 1.15)), box, kIdentity, 1e-3, "fine ball on corner",
                300);
  // And the coarse box as the probe against the fine ball.
  Model small_box = CollisionModel::Build(MakeBox(Vector3(0.1, 0.1, 0.1)));
  SolveAndCheck(small_box, At(Vector3(0.05, 0, 0.36), Quaternion(0.95, 0.1, 0.2, 0.0)), fine,
                kIdentity, 1e-3, "coarse box on fine ball", 300);
}

// Models of 1e-4 m and 1e3 m give the unit answer times the scale, as exactly
// as the reference says, with the same iterations.
TEST(HardCases, TinyAndHugeScales) {
  const TriangleMesh ball = MakeIcosphere(0.5, 2);
  const TriangleMesh knot = MakeTorusKnot(2, 3, 0.2, 1.0, 64, 6);
  const Isometry3 X_WP = At(Vector3(0.9, 0.2, 0.1), Quaternion(0.9, 0.2, -0.3, 0.1));
  auto scaled = [](TriangleMesh mesh, double s) {
    for (Vector3& v : mesh.vertices) v *= s;
    return CollisionModel::Build(std::move(mesh));
  };
  PenetrationResult unit;
  for (double scale : {1.0, 1e-4, 1e3}) {
    const Isometry3 X = At(scale * X_WP.translation(), Quaternion(X_WP.linear()));
    const Checked c = SolveAndCheck(scaled(ball, scale), X, scaled(knot, scale), kIdentity, 0.02,
                                    "ball on knot, scale " + std::to_string(scale), 300);
    ASSERT_TRUE(c.fast.in_collision);
    if (scale == 1.0) {
      unit = c.fast;
      continue;
    }
    EXPECT_NEAR(c.fast.depth / scale, unit.depth, 1e-6 * unit.depth) << "scale " << scale;
    EXPECT_GT(c.fast.normal_W.dot(unit.normal_W), 1.0 - 1e-9) << "scale " << scale;
    EXPECT_EQ(c.fast.iterations, unit.iterations) << "scale " << scale;
  }
}

// A box whose faces are fans around extra vertices lying on (or 1e-12 of
// size off) its edges: zero-area and sliver triangles; plus every vertex
// duplicated and half of the triangles moved to the copies (seams).
TEST(HardCases, SliversAndDuplicateVertices) {
  const double h = 0.5;
  TriangleMesh sliver = MakeBox(Vector3(h, h, h));
  // Split every triangle at the midpoint of its first edge, nudged outward
  // by 1e-12 * h: two slivers-to-be per split when applied twice.
  for (int pass = 0; pass < 2; ++pass) {
    const int n = sliver.num_triangles();
    for (int f = 0; f < n; ++f) {
      const Eigen::Vector3i t = sliver.triangles[f];
      const Vector3 a = sliver.vertices[t[0]], b = sliver.vertices[t[1]], c = sliver.vertices[t[2]];
      const Vector3 n_out = (b - a).cross(c - a).normalized();
      sliver.vertices.push_back(0.5 * (a + b) + 1e-12 * h * n_out);
      const int m = sliver.num_vertices() - 1;
      sliver.triangles[f] = Eigen::Vector3i(t[0], m, t[2]);
      sliver.triangles.push_back(Eigen::Vector3i(m, t[1], t[2]));
    }
  }
  Model S = CollisionModel::Build(sliver);
  Model P = CollisionModel::Build(MakeIcosphere(0.1, 2));
  Checked c = SolveAndCheck(P, At(Vector3(0.1, 0.2, 0.57)), S, kIdentity, 1e-3, "ball on sliver box");
  EXPECT_NEAR(c.fast.depth, c.ref.depth, 1e-3 * c.ref.depth);
  c = SolveAndCheck(P, At(Vector3(0.55, 0.55, 0.1)), S, kIdentity, 1e-3, "ball on sliver edge");

  TriangleMesh dup = MakeBox(Vector3(h, h, h));
  const int nv = dup.num_vertices();
  for (int v = 0; v < nv; ++v) dup.vertices.push_back(dup.vertices[v]);
  for (int f = 0; f < dup.num_triangles(); f += 2) dup.triangles[f] += Eigen::Vector3i::Constant(nv);
  Model D = CollisionModel::Build(dup);
  EXPECT_FALSE(D->closed());  // the seams open it
  c = SolveAndCheck(P, At(Vector3(0.1, -0.2, 0.55)), D, kIdentity, 1e-3, "ball on duplicated box");
  EXPECT_NEAR(c.fast.depth, 0.05, 1e-3 * 0.05);
}

// An open box (no top face) and a polygon soup (every triangle with its own
// three vertices): no solid, so only crossing surfaces collide, and the
// inside of the box is free space. A probe that reached a wall from inside
// (coherent, as in the haptic loop) is pushed back inside by the exact
// amount. Known limitation, measured here: a cold query cannot find the
// inside, since every cold start lies outside the models' hulls, so it
// returns the outside exit: still a valid, verified local PD, exact along its
// own direction, but 0.14 where the reference says 0.06.
TEST(HardCases, OpenMeshAndPolygonSoup) {
  const double h = 0.5;
  const TriangleMesh closed = MakeBox(Vector3(h, h, h));
  TriangleMesh open;
  open.vertices = closed.vertices;
  for (const Eigen::Vector3i& t : closed.triangles) {
    const bool top = closed.vertices[t[0]].z() > 0 && closed.vertices[t[1]].z() > 0 &&
                     closed.vertices[t[2]].z() > 0;
    if (!top) open.triangles.push_back(t);
  }
  ASSERT_EQ(open.num_triangles(), 10);
  TriangleMesh soup;
  for (const Eigen::Vector3i& t : closed.triangles) {
    const int base = soup.num_vertices();
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(closed.vertices[t[k]]);
    soup.triangles.push_back(Eigen::Vector3i(base, base + 1, base + 2));
  }
  Model P = CollisionModel::Build(MakeBox(Vector3(0.1, 0.1, 0.1)));
  for (const auto& [name, mesh] : {std::pair<std::string, TriangleMesh>{"open box", open},
                                   std::pair<std::string, TriangleMesh>{"polygon soup", soup}}) {
    Model S = CollisionModel::Build(mesh);
    EXPECT_FALSE(S->closed()) << name;
    // Through the floor from below: 0.03 of the probe is inside the floor
    // plane; leaving down (0.03) is shortest.
    Checked c = SolveAndCheck(P, At(Vector3(0.1, 0.1, -h - 0.1 + 0.03)), S, kIdentity, 1e-6,
                              name + ": through the floor");
    EXPECT_NEAR(c.fast.depth, 0.03, 1e-6 * 0.03) << name;
    // Across a side wall near the top, reached from inside.
    const Isometry3 X_wall = At(Vector3(h - 0.04, 0.0, 0.3));
    PolyDepthSolver coherent(P, S);
    PenetrationResult r;
    // 5 mm steps; at x = 0.4 the probe touches the wall exactly, where the
    // escape direction is arbitrary: coherence must not follow it outside.
    for (int i = 0; i < 92; ++i) coherent.Solve(At(Vector3(0.005 * i, 0, 0.3)), kIdentity, true);
    r = coherent.Solve(X_wall, kIdentity, true);  // x = 0.46
    ASSERT_TRUE(r.in_collision && r.valid) << name;
    const ReferencePdResult ref =
        ReferencePenetrationDepth(P->mesh(), X_wall, true, S->mesh(), kIdentity, false);
    EXPECT_NEAR(ref.depth, 0.06, 1e-6 * 0.06) << name;
    EXPECT_NEAR(r.depth, ref.depth, 1e-6 * ref.depth + Slack(P, S)) << name;
    EXPECT_LT(r.normal_W.x(), -0.999) << name;
    EXPECT_LE(r.iterations, IterationBound(coherent.options())) << name;
    // Cold: the outside exit, valid and exact along its direction.
    PolyDepthSolver cold(P, S);
    const PenetrationResult o = cold.Solve(X_wall, kIdentity);
    ASSERT_TRUE(o.in_collision && o.valid) << name;
    EXPECT_FALSE(ReferenceInCollision(P->mesh(), X_wall, true, S->mesh(), kIdentity, false,
                                      o.translation_W)) << name;
    EXPECT_NEAR(DirectionalPenetration(P->mesh(), X_wall, true, S->mesh(), kIdentity, false,
                                       o.normal_W, 1e-9 * PairSize(P, S)),
                o.depth, 1e-6 * o.depth + Slack(P, S)) << name;
    std::printf("[ case     ] %-44s coherent %.6g cold %.6g ref %.6g (cold: outside exit)\n",
                (name + ": across a wall").c_str(), r.depth, o.depth, ref.depth);
    // Wholly inside the walls without touching: free for a surface model.
    c = SolveAndCheck(P, At(Vector3(0, 0, 0)), S, kIdentity, 1e-6, name + ": inside, not touching");
    EXPECT_FALSE(c.fast.in_collision) << name;
  }
}

// A needle (thin cylinder, 100:1) tip-first into a face, lying flat on it,
// and pushed tip-first through a thin plate with motion coherence: it is
// always pushed back the way it came (no pop-through), by exactly how far it
// went in.
TEST(HardCases, NeedlesAndThinWalls) {
  const double r = 0.002, len = 0.4;
  Model needle = CollisionModel::Build(MakeCylinder(r, len, 8));
  Model box = CollisionModel::Build(MakeBox(Vector3(1, 1, 1)));
  Checked c = SolveAndCheck(needle, At(Vector3(0.1, 0.1, 1.0 + len / 2 - 0.03)), box, kIdentity,
                            1e-6, "needle tip-first");
  EXPECT_NEAR(c.fast.depth, 0.03, 1e-6 * 0.03);
  EXPECT_GT(c.fast.normal_W.z(), 0.999);
  c = SolveAndCheck(needle, At(Vector3(0, 0.2, 1.0 + r - 0.001), Quaternion(Eigen::AngleAxisd(M_PI / 2, Vector3::UnitY()))),
                    box, kIdentity, 1e-3, "needle lying on the face");
  EXPECT_NEAR(c.fast.depth, c.ref.depth, 1e-3 * c.ref.depth);

  Model plate = CollisionModel::Build(MakeThinPlate(1.0, 1.0, 0.005));
  PolyDepthSolver coherent(needle, plate);
  int colliding = 0;
  // Tip from 1 cm above the plate to 3/4 of the needle through it.
  for (double tip = 0.01; tip > -0.75 * len; tip -= 0.002) {
    const Isometry3 X_WP = At(Vector3(0.05, -0.02, tip + len / 2));
    const PenetrationResult res = coherent.Solve(X_WP, kIdentity, true);
    if (!res.in_collision) {
      ASSERT_EQ(colliding, 0) << "lost contact inside the plate, tip z=" << tip;
      continue;
    }
    ++colliding;
    ASSERT_TRUE(res.valid) << "tip z=" << tip;
    ASSERT_TRUE(std::isfinite(res.depth));
    EXPECT_LE(res.iterations, IterationBound(coherent.options()));
    EXPECT_GT(res.normal_W.z(), 0.999) << "popped through at tip z=" << tip;
    EXPECT_NEAR(res.depth, 0.005 - tip, 1e-6 * len) << "tip z=" << tip;
  }
  EXPECT_GT(colliding, 100);
}

}  // namespace
}  // namespace pd
