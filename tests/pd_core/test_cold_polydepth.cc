// Cold PolyDepth (issue 13): queries without a previous answer on pairs of
// real closed meshes, checked against the independent reference PD (no hint
// from the solver), for freedom beyond the answer, determinism and scale
// invariance; and the early stop of cold starts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "pd_core/geometry/make_shapes.h"
#include "pd_core/polydepth/cold_starts.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/pd_core/normalised_mesh.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using Model = std::shared_ptr<const CollisionModel>;
const std::string kMeshDir = PD_TEST_MESH_DIR;

using test::LoadNormalised;

// The benchmark's random scenario: random orientation, probe box centre at
// U[0.1, 0.8] scene radii from the scene's, colliding poses only.
std::vector<Isometry3> RandomCollidingPoses(const Model& P, const Model& S, const Isometry3& X_WS,
                                            int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> frac(0.1, 0.8);
  std::vector<Isometry3> poses;
  for (int tries = 0; tries < 50 * count && static_cast<int>(poses.size()) < count; ++tries) {
    Isometry3 X = Isometry3::Identity();
    X.linear() = Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    const Vector3 u = Vector3(g(rng), g(rng), g(rng)).normalized();
    X.translation() = X_WS * S->center() + frac(rng) * S->radius() * u - X.linear() * P->center();
    if (InCollision(ModelPair(*P, *S, X, X_WS), Vector3::Zero())) poses.push_back(X);
  }
  return poses;
}

// Two meshes (probe, scene; the caller requires the files) normalised, the
// scene at the origin, and six random colliding poses of the probe.
struct ColdPoses {
  Model P, S;
  Isometry3 X_WS = Isometry3::Identity();
  std::vector<Isometry3> poses;
};
ColdPoses LoadColdPoses(const std::string& probe, const std::string& scene, uint64_t seed) {
  ColdPoses c;
  c.P = CollisionModel::Build(LoadNormalised(probe));
  c.S = CollisionModel::Build(LoadNormalised(scene));
  c.poses = RandomCollidingPoses(c.P, c.S, c.X_WS, 6, seed);
  return c;
}

struct PairCase {
  const char* probe;
  const char* scene;
  uint64_t seed;
};

// Pairs whose cold answers the old start selection (3 maximally clear
// starts) got wrong by 13% to 400% on some of these poses.
const PairCase kPairs[] = {
    {"rotor_small.off", "blobby.off", 1},
    {"cow.off", "cow.off", 2},
    {"bones.off", "couplingdown.off", 3},
};

class ColdRealPairs : public ::testing::TestWithParam<PairCase> {};

// Each cold answer is verified free by the reference's own collision test,
// also 2e-6 of the pair's size further along it, touches (collides 1e-5 of
// the size back toward the query), and is no more than 10% (issue 13's max;
// mean over the pair's poses 2%) above the reference PD (an upper bound
// itself: 128 directions). With 3 iterated starts and no shell the worst
// pose here was +38% (rotor/blobby); with the shell +1.4% (bones/coupling).
TEST_P(ColdRealPairs, AnswersAreFreeAndNearTheReference) {
  const PairCase c = GetParam();
  PD_REQUIRE_FILE(kMeshDir + "/" + c.probe, "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/" + c.scene, "run scripts/fetch_meshes.sh");
  const Model P = CollisionModel::Build(LoadNormalised(c.probe));
  const Model S = CollisionModel::Build(LoadNormalised(c.scene));
  ASSERT_TRUE(P->closed() && S->closed());
  const Isometry3 X_WS = Isometry3::Identity();
  const std::vector<Isometry3> poses = RandomCollidingPoses(P, S, X_WS, 4, c.seed);
  ASSERT_EQ(poses.size(), 4u);
  const double size = P->radius() + S->radius();
  double sum = 0.0;
  for (size_t i = 0; i < poses.size(); ++i) {
    PolyDepthSolver solver(P, S);
    const PenetrationResult r = solver.Solve(poses[i], X_WS);
    ASSERT_TRUE(r.in_collision && r.valid) << "pose " << i;
    EXPECT_GE(r.starts, 1) << "pose " << i;
    EXPECT_FALSE(ReferenceInCollision(P->mesh(), poses[i], true, S->mesh(), X_WS, true,
                                      r.translation_W))
        << "pose " << i;
    const Vector3 beyond = r.translation_W * (1.0 + 2e-6 * size / r.depth);
    EXPECT_FALSE(ReferenceInCollision(P->mesh(), poses[i], true, S->mesh(), X_WS, true, beyond))
        << "pose " << i << ": not free 2e-6 of size further out";
    // On the contact space: 1e-5 of size back toward the query collides (a
    // free answer with a gap would be deeper than needed).
    const Vector3 back = r.translation_W * (1.0 - 1e-5 * size / r.depth);
    EXPECT_TRUE(ReferenceInCollision(P->mesh(), poses[i], true, S->mesh(), X_WS, true, back))
        << "pose " << i << ": the answer does not touch";
    ReferencePdOptions ro;
    ro.num_directions = 128;
    ro.refine_iterations = 24;
    const ReferencePdResult ref =
        ReferencePenetrationDepth(P->mesh(), poses[i], true, S->mesh(), X_WS, true, ro);
    ASSERT_TRUE(ref.in_collision);
    const double err = (r.depth - ref.depth) / ref.depth;
    std::printf("[ case     ] %s/%s pose %zu: depth %.6f reference %.6f error %+.4f, %d "
                "iterations, %d starts\n",
                c.probe, c.scene, i, r.depth, ref.depth, err, r.iterations, r.starts);
    EXPECT_LE(err, 0.10) << "pose " << i;
    sum += std::max(err, 0.0);
  }
  EXPECT_LE(sum / poses.size(), 0.02);
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, ColdRealPairs, ::testing::ValuesIn(kPairs),
                         [](const ::testing::TestParamInfo<PairCase>& info) {
                           std::string n = std::string(info.param.probe) + "_" + info.param.scene;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

// A pose of the benchmark's dino_femur pair (random case 51 at seed
// 20240611, as the relative pose X_SP of the normalised meshes): the
// shortest escape, 4.7 mm, leads into a pocket the femur encloses (free
// from 4.7 to about 7.5 mm along its direction, shut again beyond), while
// every landing from outside comes in at 36 mm or more. The default cold
// query must find it (its deep probes, PolyDepthOptions::cold_deep_probes:
// with them off the answer was 35.9 mm, +663%): within 10% (issue 13's max)
// of the independent reference, and free 2e-6 of the size further out.
TEST(ColdPolyDepth, EnclosedPocketEscapeIsFound) {
  PD_REQUIRE_FILE(kMeshDir + "/dino.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/femur.off", "run scripts/fetch_meshes.sh");
  const Model P = CollisionModel::Build(LoadNormalised("dino.off"));
  const Model S = CollisionModel::Build(LoadNormalised("femur.off"));
  const Isometry3 X_WS = Isometry3::Identity();
  Isometry3 X_WP = Isometry3::Identity();
  X_WP.linear() = Quaternion(0.020889903674742531, 0.38035437499551661, 0.47635878676871835,
                             0.79244966251142079)
                      .normalized()
                      .toRotationMatrix();
  X_WP.translation() = Vector3(-0.0079832911339176964, 0.069687024632379066,
                               0.013324227408144294);
  const PenetrationResult r = PolyDepthSolver(P, S).Solve(X_WP, X_WS);
  ASSERT_TRUE(r.in_collision && r.valid);
  ReferencePdOptions ro;
  ro.num_directions = 512;
  ro.refine_iterations = 64;
  const ReferencePdResult ref =
      ReferencePenetrationDepth(P->mesh(), X_WP, true, S->mesh(), X_WS, true, ro);
  ASSERT_TRUE(ref.in_collision);
  std::printf("[ case     ] dino/femur: depth %.6f reference %.6f\n", r.depth, ref.depth);
  // The pocket, as the reference sees it: free past its answer, shut at
  // twice its length (so an escape there is not a plain outside one).
  EXPECT_TRUE(ReferenceInCollision(P->mesh(), X_WP, true, S->mesh(), X_WS, true,
                                   2.0 * ref.translation_W));
  EXPECT_LE(r.depth, 1.10 * ref.depth);
  const double size = P->radius() + S->radius();
  EXPECT_FALSE(ReferenceInCollision(P->mesh(), X_WP, true, S->mesh(), X_WS, true,
                                    r.translation_W * (1.0 + 2e-6 * size / r.depth)));
}

// Same query, same answer: on a fresh solver, again on the same solver after
// other cold queries (random starts are drawn from the seed per query), bit
// for bit.
TEST(ColdPolyDepth, SameQuerySameAnswer) {
  PD_REQUIRE_FILE(kMeshDir + "/elk.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/hand.off", "run scripts/fetch_meshes.sh");
  const Model P = CollisionModel::Build(LoadNormalised("elk.off"));
  const Model S = CollisionModel::Build(LoadNormalised("hand.off"));
  const Isometry3 X_WS = Isometry3::Identity();
  const std::vector<Isometry3> poses = RandomCollidingPoses(P, S, X_WS, 3, 7);
  ASSERT_EQ(poses.size(), 3u);
  PolyDepthSolver shared(P, S);
  std::vector<PenetrationResult> first;
  for (const Isometry3& X : poses) first.push_back(shared.Solve(X, X_WS));
  for (int round = 0; round < 2; ++round) {
    for (size_t i = 0; i < poses.size(); ++i) {
      PolyDepthSolver fresh(P, S);
      for (const PenetrationResult& r : {shared.Solve(poses[i], X_WS), fresh.Solve(poses[i], X_WS)}) {
        EXPECT_EQ(r.translation_W, first[i].translation_W) << "pose " << i << " round " << round;
        EXPECT_EQ(r.iterations, first[i].iterations) << "pose " << i;
        EXPECT_EQ(r.starts, first[i].starts) << "pose " << i;
        EXPECT_EQ(r.initializer, first[i].initializer) << "pose " << i;
      }
    }
  }
}

// Scaling both meshes and the poses by 1e-2 or 1e2 scales the cold answer and
// changes nothing else (every tolerance is relative to the pair's size).
TEST(ColdPolyDepth, RealPairIsScaleInvariant) {
  PD_REQUIRE_FILE(kMeshDir + "/rotor_small.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/blobby.off", "run scripts/fetch_meshes.sh");
  const Model P1 = CollisionModel::Build(LoadNormalised("rotor_small.off"));
  const Model S1 = CollisionModel::Build(LoadNormalised("blobby.off"));
  const Isometry3 X_WS = Isometry3::Identity();
  const std::vector<Isometry3> poses = RandomCollidingPoses(P1, S1, X_WS, 3, 11);
  ASSERT_EQ(poses.size(), 3u);
  for (double scale : {1e-2, 1e2}) {
    const Model P = CollisionModel::Build(LoadNormalised("rotor_small.off", scale));
    const Model S = CollisionModel::Build(LoadNormalised("blobby.off", scale));
    for (size_t i = 0; i < poses.size(); ++i) {
      const PenetrationResult base = PolyDepthSolver(P1, S1).Solve(poses[i], X_WS);
      Isometry3 X = poses[i];
      X.translation() *= scale;
      const PenetrationResult r = PolyDepthSolver(P, S).Solve(X, X_WS);
      ASSERT_TRUE(base.valid && r.valid) << "pose " << i << " scale " << scale;
      // Round-off through ~15 CCD iterations: 1e-5 relative.
      EXPECT_NEAR(r.depth / scale, base.depth, 1e-5 * base.depth) << "pose " << i << " scale " << scale;
      EXPECT_GT(r.normal_W.dot(base.normal_W), 1.0 - 1e-9) << "pose " << i << " scale " << scale;
      EXPECT_EQ(r.iterations, base.iterations) << "pose " << i << " scale " << scale;
      EXPECT_EQ(r.starts, base.starts) << "pose " << i << " scale " << scale;
    }
  }
}

// The cold starts the join and screening knobs were measured with: 8
// support-plane landings and 2 random ones, 4 of them iterated (ungated).
PolyDepthOptions FourIteratedStarts() {
  PolyDepthOptions o;
  o.num_maximally_clear = 8;
  o.num_random = 2;
  o.num_iterated_starts = 4;
  o.cold_start_gate = 1e300;
  return o;
}

// With PolyDepthOptions::cold_join (off by default) a cold start whose
// iterate comes near where an earlier start went (and ended no deeper)
// stops there: less work over the starts, the same answers within 1% on
// these poses (the joined optimum is already the best's candidate). With the
// join off, the same poses cost more: a join that never fires fails here.
TEST(ColdPolyDepth, StartsJoiningAnEarlierStartsDescentSaveWorkNotDepth) {
  PD_REQUIRE_FILE(kMeshDir + "/elephant.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/cow.off", "run scripts/fetch_meshes.sh");
  const ColdPoses c = LoadColdPoses("elephant.off", "cow.off", 5);
  ASSERT_EQ(c.poses.size(), 6u);
  const auto& [P, S, X_WS, poses] = c;
  // Measured with 4 iterated starts of 8 support-plane landings and 2
  // random ones (the defaults then): the join saves work where several
  // starts descend into one optimum.
  const PolyDepthOptions off = FourIteratedStarts();
  ASSERT_EQ(off.cold_join, 0.0);
  PolyDepthOptions on = off;
  on.cold_join = 2e-2;
  int64_t work_on = 0, work_off = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const PenetrationResult a = PolyDepthSolver(P, S, on).Solve(poses[i], X_WS);
    const PenetrationResult b = PolyDepthSolver(P, S, off).Solve(poses[i], X_WS);
    ASSERT_TRUE(a.valid && b.valid) << "pose " << i;
    work_on += a.box_tests + a.triangle_tests;
    work_off += b.box_tests + b.triangle_tests;
    EXPECT_LE(a.depth, 1.01 * b.depth) << "pose " << i;
    EXPECT_LE(a.iterations, b.iterations) << "pose " << i;
  }
  std::printf("[ work     ] elephant/cow, 6 cold poses: %lld tests with the join, %lld without\n",
              static_cast<long long>(work_on), static_cast<long long>(work_off));
  EXPECT_LT(work_on, 0.95 * work_off);
}

// A cold query lands the best num_maximally_clear of max(that, 48)
// support-plane directions (96 by default) and the centroid start, every
// one counted in `starts` (with the shell and inner probes it
// out-projects), and
// iterates num_iterated_starts of them, counted in `iterated_starts`. (What
// more landings buy in accuracy is bench_pd's to measure: PolyDepthOptions
// documents it.)
TEST(ColdPolyDepth, EverySupportPlaneStartIsLandedAndCounted) {
  PD_REQUIRE_FILE(kMeshDir + "/elephant.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/cow.off", "run scripts/fetch_meshes.sh");
  const ColdPoses c = LoadColdPoses("elephant.off", "cow.off", 5);
  PolyDepthOptions no_inner;
  no_inner.cold_inner_probes = 0;
  no_inner.cold_shell_probes = 0;
  ASSERT_EQ(no_inner.num_maximally_clear, 96);
  ASSERT_EQ(no_inner.num_random, 0);
  PolyDepthOptions few = no_inner;
  few.num_maximally_clear = 8;
  // `iterated_starts` counts the searches a query ran: with the gate open
  // (every one of the closest landings is iterated) and no shell or inner
  // probes, exactly num_iterated_starts (1 or 3); with the shell, its free
  // probes are iterated too (up to 4).
  PolyDepthOptions ungated[2], shell[2];
  const int iterated[2] = {1, 3};
  for (int k = 0; k < 2; ++k) {
    ungated[k] = no_inner;
    ungated[k].cold_start_gate = 1e300;
    ungated[k].num_iterated_starts = iterated[k];
    shell[k] = ungated[k];
    shell[k].cold_shell_probes = 256;
  }
  for (size_t i = 0; i < c.poses.size(); ++i) {
    auto solve = [&](const PolyDepthOptions& o) {
      return PolyDepthSolver(c.P, c.S, o).Solve(c.poses[i], c.X_WS);
    };
    const PenetrationResult a = solve(no_inner), b = solve(few);
    ASSERT_TRUE(a.valid && b.valid) << "pose " << i;
    EXPECT_EQ(a.starts, 96 + 1) << "pose " << i;
    EXPECT_EQ(b.starts, 8 + 1) << "pose " << i;
    for (int k = 0; k < 2; ++k) {
      const PenetrationResult u = solve(ungated[k]), w = solve(shell[k]);
      ASSERT_TRUE(u.valid && w.valid) << "pose " << i;
      EXPECT_EQ(u.iterated_starts, iterated[k]) << "pose " << i;
      EXPECT_GE(w.iterated_starts, iterated[k]) << "pose " << i;
      EXPECT_LE(w.iterated_starts, iterated[k] + 4) << "pose " << i;
      EXPECT_GE(u.iterations, u.iterated_starts) << "pose " << i;
    }
  }
}

// The shell (PolyDepthOptions::cold_shell_probes): after the iterated
// starts, probes at 0.995 of the answer's length in 256 directions find the
// other basins shallower than it. On these poses (found by scanning 216
// random poses of 6 pairs) the iterated starts end in a basin 9-11% deeper
// than the shell's answer, which is free (the reference's own collision
// test) and no more than 1% above the reference (which never sees the
// solver's answer; here it is the reference that is deeper, by 5-12%).
TEST(ColdPolyDepth, ShellProbesFindTheShallowerBasinTheStartMisses) {
  struct ShellCase {
    const char* probe;
    const char* scene;
    uint64_t seed;
    size_t pose;
  };
  const ShellCase cases[] = {{"cow.off", "cow.off", 5, 4},
                             {"cow.off", "cow.off", 1, 4},
                             {"dino.off", "femur.off", 2, 3}};
  for (const ShellCase& k : cases) {
    PD_REQUIRE_FILE(kMeshDir + "/" + k.probe, "run scripts/fetch_meshes.sh");
    PD_REQUIRE_FILE(kMeshDir + "/" + k.scene, "run scripts/fetch_meshes.sh");
    const ColdPoses c = LoadColdPoses(k.probe, k.scene, k.seed);
    ASSERT_GT(c.poses.size(), k.pose);
    const Isometry3& X_WP = c.poses[k.pose];
    PolyDepthOptions no_shell;
    no_shell.cold_shell_probes = 0;
    const PenetrationResult with = PolyDepthSolver(c.P, c.S).Solve(X_WP, c.X_WS);
    const PenetrationResult without = PolyDepthSolver(c.P, c.S, no_shell).Solve(X_WP, c.X_WS);
    ASSERT_TRUE(with.valid && without.valid) << k.probe;
    ReferencePdOptions ro;
    ro.num_directions = 128;
    ro.refine_iterations = 24;
    const ReferencePdResult ref = ReferencePenetrationDepth(c.P->mesh(), X_WP, true, c.S->mesh(),
                                                            c.X_WS, true, ro);
    std::printf("[ case     ] %s/%s seed %llu pose %zu: shell %.6f, without %.6f, reference "
                "%.6f\n",
                k.probe, k.scene, static_cast<unsigned long long>(k.seed), k.pose, with.depth,
                without.depth, ref.depth);
    EXPECT_GT(without.depth, 1.05 * with.depth) << k.probe << ": the shell found nothing";
    EXPECT_LE(with.depth, 1.01 * ref.depth) << k.probe;
    EXPECT_FALSE(ReferenceInCollision(c.P->mesh(), X_WP, true, c.S->mesh(), c.X_WS, true,
                                      with.translation_W))
        << k.probe;
  }
}

// Screening (PolyDepthOptions::cold_screen_tol, a speed-for-accuracy knob,
// off by default): the iterated starts stop at the coarse tolerance and only
// the best goes on. On these poses it saves a fifth of the work or more;
// each answer stays within 2% of the unscreened one (a start ending behind
// can overtake once it slows down: that is the trade) and the mean within
// 0.5%.
TEST(ColdPolyDepth, ScreenedStartsSaveWorkNotDepth) {
  PD_REQUIRE_FILE(kMeshDir + "/knot1.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/cow.off", "run scripts/fetch_meshes.sh");
  const ColdPoses c = LoadColdPoses("knot1.off", "cow.off", 8);
  ASSERT_EQ(c.poses.size(), 6u);
  const auto& [P, S, X_WS, poses] = c;
  // With several iterated starts to screen (as measured: see
  // FourIteratedStarts).
  const PolyDepthOptions off = FourIteratedStarts();
  ASSERT_LE(off.cold_screen_tol, off.convergence_tol);
  PolyDepthOptions on = off;
  on.cold_screen_tol = 1e-3;
  int64_t work_on = 0, work_off = 0;
  double depth_on = 0.0, depth_off = 0.0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const PenetrationResult a = PolyDepthSolver(P, S, on).Solve(poses[i], X_WS);
    const PenetrationResult b = PolyDepthSolver(P, S, off).Solve(poses[i], X_WS);
    ASSERT_TRUE(a.valid && b.valid) << "pose " << i;
    EXPECT_FALSE(InCollision(ModelPair(*P, *S, poses[i], X_WS),
                             X_WS.linear().transpose() * a.translation_W))
        << "pose " << i;
    work_on += a.box_tests + a.triangle_tests;
    work_off += b.box_tests + b.triangle_tests;
    depth_on += a.depth;
    depth_off += b.depth;
    EXPECT_LE(a.depth, 1.02 * b.depth) << "pose " << i;
    std::printf("[ case     ] knot1/cow pose %zu: depth %.6f screened, %.6f not; %d vs %d "
                "iterations\n",
                i, a.depth, b.depth, a.iterations, b.iterations);
  }
  std::printf("[ work     ] knot1/cow, 6 cold poses: %lld tests screened, %lld not\n",
              static_cast<long long>(work_on), static_cast<long long>(work_off));
  EXPECT_LT(work_on, 0.8 * work_off);
  EXPECT_LE(depth_on, 1.005 * depth_off);
}

// A cold answer is backed off the contact by exactly one separation margin,
// also where the final polish (the best answer's local model solved once
// more) sets it: a needle lying into a flat face, whose PD is how far its
// lowest edge went in. (The polish once reused constraints an iteration had
// already moved by the margin: two margins.)
TEST(ColdPolyDepth, AnAnswerIsOneSeparationMarginClearOfTheContact) {
  const Model needle = CollisionModel::Build(MakeCylinder(0.002, 0.4, 8));
  const Model box = CollisionModel::Build(MakeBox(Vector3(1, 1, 1)));
  Isometry3 X_WP = Isometry3::Identity();
  X_WP.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3::UnitY()).toRotationMatrix();
  double lowest = 1e300;
  for (const Vector3& v : needle->mesh().vertices) lowest = std::min(lowest, (X_WP.linear() * v).z());
  for (int iterated : {1, 3}) {
    PolyDepthOptions options;
    options.num_iterated_starts = iterated;
    PolyDepthSolver solver(needle, box, options);
    const double margin = options.separation_margin * (needle->radius() + box->radius());
    for (double in : {0.0005, 0.001, 0.0013}) {
      X_WP.translation() = Vector3(0, 0.2, 1.0 - lowest - in);
      const PenetrationResult r = solver.Solve(X_WP, Isometry3::Identity());
      ASSERT_TRUE(r.in_collision && r.valid);
      EXPECT_GT(r.normal_W.z(), 0.999);
      EXPECT_NEAR(r.depth - in, margin, 0.25 * margin)
          << iterated << " iterated starts, " << in << " m in: " << (r.depth - in) / margin
          << " margins clear";
    }
  }
}

// The early stop extrapolates a geometric descent: a start heading for a
// limit above the best answer stops, one heading below it goes on.
TEST(StartAbandon, StopsOnlyStartsThatCannotBeatTheBest) {
  auto steps_until_stop = [](double best, double limit, double start, double ratio) {
    StartAbandon a(best);
    double norm = start, drop = 0.5 * (start - limit);
    if (a.Update(norm)) return 0;
    for (int k = 1; k < 60; ++k) {
      norm -= drop;
      drop *= ratio;
      if (a.Update(norm)) return k;
    }
    return -1;
  };
  // Converging to 1.5 with best 1.0: stopped within a few steps.
  const int stopped = steps_until_stop(1.0, 1.5, 3.0, 0.5);
  EXPECT_GT(stopped, 0);
  EXPECT_LE(stopped, 3);
  // Converging to 0.9 (beats 1.0), slowly or fast: never stopped.
  EXPECT_EQ(steps_until_stop(1.0, 0.9, 3.0, 0.5), -1);
  EXPECT_EQ(steps_until_stop(1.0, 0.9, 3.0, 0.9), -1);
  // Within the 2% slack of the best: kept.
  EXPECT_EQ(steps_until_stop(1.0, 1.01, 3.0, 0.5), -1);
  // No progress is the iteration's own stop, not the abandon's.
  StartAbandon flat(1.0);
  EXPECT_FALSE(flat.Update(2.0));
  EXPECT_FALSE(flat.Update(2.0));
  EXPECT_FALSE(flat.Update(2.0));
}

}  // namespace
}  // namespace pd
