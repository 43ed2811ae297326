// The broad phase (haptics/contact/broad_phase.h): never culls a pair that touches
// (random sweeps against brute-force PD of every pair), returns exactly the
// objects whose boxes overlap the query, culls far objects and planes the
// tool is above, and keeps the servo tick allocation-free and cold-starting
// objects that left reach.
#include "haptics/contact/broad_phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "alloc_counter.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics/contact/penalty_wrench.h"
#include "haptics_test_util.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/mesh/model_cache.h"
#include "pd_core/convex/gjk.h"
#include "pd_core/convex/minkowski_difference.h"

namespace haptics {
namespace {

Isometry3 RandomPose(std::mt19937_64& rng, double extent) {
  std::uniform_real_distribution<double> u(-extent, extent);
  std::normal_distribution<double> g;
  Isometry3 X = Isometry3::Identity();
  X.linear() = Quaternion(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  X.translation() = Vector3(u(rng), u(rng), u(rng));
  return X;
}

// A random crowd of every kind in a 20 cm cube, one plane in eight.
std::vector<SceneObject> RandomObjects(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> size(0.004, 0.02);
  const auto convex = pd::Geometry::MakeConvexMesh(pd::CollisionModel::Build(pd::MakeIcosphere(0.015, 1)));
  const auto torus = pd::Geometry::MakeMesh(pd::CollisionModel::Build(pd::MakeTorus(0.015, 0.005, 16, 8)));
  std::vector<SceneObject> objects;
  for (int i = 0; i < n; ++i) {
    SceneObject o;
    o.name = "object_" + std::to_string(i);
    o.X_WS = RandomPose(rng, 0.1);
    switch (i % 8) {
      case 0: o.geometry = pd::Geometry::MakeSphere(size(rng)); break;
      case 1: o.geometry = pd::Geometry::MakeBox(Vector3(size(rng), size(rng), size(rng))); break;
      case 2: o.geometry = pd::Geometry::MakeCapsule(size(rng), size(rng)); break;
      case 3: o.geometry = pd::Geometry::MakeCylinder(size(rng), size(rng)); break;
      case 4: o.geometry = convex; break;
      case 5: o.geometry = torus; break;
      case 6: o.geometry = pd::Geometry::MakeBox(Vector3(0.05, 0.002, 0.03)); break;
      default:
        // Planes through a point below the centre, turned at random.
        o.geometry = pd::Geometry::MakeHalfSpace();
        o.X_WS.translation() = Vector3(0, 0, i < n / 2 ? -0.12 : -0.09);
        break;
    }
    objects.push_back(std::move(o));
  }
  return objects;
}

// Brute force: do the convex hulls of tool P at X_WP and object S at X_WS
// touch (GJK on their support functions; a plane: the tool's lowest point
// along its normal)? Touching shapes have touching hulls, so every pair this
// says touches must survive the broad phase, whose boxes bound the hulls.
bool HullsTouch(const pd::Geometry& P, const Isometry3& X_WP, const pd::Geometry& S, const Isometry3& X_WS) {
  if (!S.bounded()) {
    const Vector3 n_W = X_WS.linear().col(2);
    const Vector3 lowest_W = X_WP * P.Support(X_WP.linear().transpose() * -n_W);
    return n_W.dot(lowest_W - X_WS.translation()) <= 0.0;
  }
  const pd::MinkowskiDifference D{&P, &S, X_WP, X_WS};
  const pd::GjkResult r = pd::Gjk(D, X_WS.translation() - X_WP.translation(), 1e-12);
  return r.intersecting || r.v.norm() <= D.margin();
}

TEST(BroadPhase, NeverCullsAPairThatTouchesOverRandomSweeps) {
  std::mt19937_64 rng(7);
  const std::vector<SceneObject> objects = RandomObjects(rng, 48);
  const BroadPhase broad(objects);
  ASSERT_EQ(broad.num_planes(), 6);
  const std::vector<std::shared_ptr<const pd::Geometry>> tools = {
      pd::Geometry::MakeBox(Vector3(0.01, 0.015, 0.005)), pd::Geometry::MakeCapsule(0.006, 0.012),
      pd::Geometry::MakeSphere(0.01),
      pd::Geometry::MakeMesh(pd::CollisionModel::Build(pd::MakeSpoon(pd::SpoonDimensions{})))};
  std::vector<int> candidates;
  candidates.reserve(objects.size());
  int touching = 0, culled = 0;
  std::uniform_real_distribution<double> step(-0.004, 0.004);
  for (const auto& tool : tools) {
    for (int trial = 0; trial < 300; ++trial) {
      const Isometry3 X_prev = RandomPose(rng, 0.11);
      Isometry3 X_now = X_prev;  // a tick's motion: translation and a small turn
      X_now.translation() += Vector3(step(rng), step(rng), step(rng));
      X_now.linear() = X_now.linear() * Eigen::AngleAxisd(0.05, Vector3(step(rng), step(rng), 1).normalized()).toRotationMatrix();
      const WorldBox swept = BoundingBoxInWorld(*tool, X_prev).Joined(BoundingBoxInWorld(*tool, X_now));
      // Brute force: every pair touching at either end must be a candidate
      // of the swept box itself; one touching in between (halfway, turned as
      // at the start) a candidate of the box grown by the default cull_margin,
      // as PenaltyContact queries it.
      broad.Query(swept, &candidates);
      const std::vector<int> tight = candidates;
      broad.Query(swept.Grown(ContactConfig{}.cull_margin), &candidates);
      auto has = [](const std::vector<int>& v, int i) { return std::find(v.begin(), v.end(), i) != v.end(); };
      for (int i = 0; i < static_cast<int>(objects.size()); ++i) {
        culled += !has(candidates, i);
        Isometry3 X_mid = X_prev;
        X_mid.translation() = 0.5 * (X_prev.translation() + X_now.translation());
        const std::pair<const Isometry3*, const std::vector<int>*> checks[] = {
            {&X_prev, &tight}, {&X_now, &tight}, {&X_mid, &candidates}};
        for (const auto& [X, kept] : checks) {
          if (!HullsTouch(*tool, *X, *objects[i].geometry, objects[i].X_WS)) continue;
          ++touching;
          EXPECT_TRUE(has(*kept, i)) << "culled a touching pair: object " << i << " ("
                                     << objects[i].geometry->Describe() << "), tool " << tool->Describe();
        }
      }
    }
  }
  EXPECT_GT(touching, 200);  // the test exercised contacts
  EXPECT_GT(culled, 20000);  // and culled most pairs
}

TEST(BroadPhase, TreeReturnsExactlyTheObjectsWhoseBoxesOverlap) {
  std::mt19937_64 rng(11);
  const std::vector<SceneObject> objects = RandomObjects(rng, 101);
  const BroadPhase broad(objects);
  std::vector<int> candidates;
  std::uniform_real_distribution<double> half(0.001, 0.05);
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3 c = RandomPose(rng, 0.12).translation();
    const Vector3 h(half(rng), half(rng), half(rng));
    const WorldBox query{c - h, c + h};
    broad.Query(query, &candidates);
    std::vector<int> expected;
    for (int i = 0; i < broad.num_objects(); ++i) {
      const pd::Geometry& g = *objects[i].geometry;
      if (g.bounded()) {
        if (broad.object_box(i).Overlaps(query)) expected.push_back(i);
      } else {
        // Brute force over the box's corners: any at or below the plane.
        const Isometry3 X_SW = objects[i].X_WS.inverse();
        bool below = false;
        for (int k = 0; k < 8; ++k) {
          const Vector3 corner(k & 1 ? query.max_W.x() : query.min_W.x(), k & 2 ? query.max_W.y() : query.min_W.y(),
                               k & 4 ? query.max_W.z() : query.min_W.z());
          below |= (X_SW * corner).z() <= 0.0;
        }
        if (below) expected.push_back(i);
      }
    }
    std::sort(candidates.begin(), candidates.end());
    EXPECT_EQ(candidates, expected);
  }
  // Object boxes are tight: every box touches its object's support points.
  for (int i = 0; i < broad.num_objects(); ++i) {
    const pd::Geometry& g = *objects[i].geometry;
    if (!g.bounded()) continue;
    const Matrix3 R_SW = objects[i].X_WS.linear().transpose();
    for (int axis = 0; axis < 3; ++axis) {
      const Vector3 top_W = objects[i].X_WS * g.Support(R_SW.col(axis));
      EXPECT_NEAR(top_W[axis], broad.object_box(i).max_W[axis], 1e-12);
    }
    const WorldBox cheap = BoundingBoxInWorld(g, objects[i].X_WS);
    EXPECT_TRUE((cheap.min_W.array() <= broad.object_box(i).min_W.array() + 1e-12).all());
    EXPECT_TRUE((cheap.max_W.array() >= broad.object_box(i).max_W.array() - 1e-12).all());
  }
}

TEST(BroadPhase, FarObjectsAndPlanesBelowAreCulledAndLeaveWithAColdStart) {
  SceneConfig config = test::BoxOnBoxConfig();  // 2 cm box tool, table top at z = 0
  ObjectConfig floor;
  floor.name = "floor";
  floor.shape = {"objects[1].shape", PlaneShape{}};
  floor.X_WS.translation() = Vector3(0, 0, -0.02);
  config.objects.push_back(floor);
  ObjectConfig far_ball;
  far_ball.name = "far_ball";
  far_ball.shape = {"objects[2].shape", SphereShape{0.05}};
  far_ball.X_WS.translation() = Vector3(1.0, 0, 0);
  config.objects.push_back(far_ball);
  PenaltyContact contact(BuildSceneModels(config), config.contact);
  RigidState tool;
  // High above everything: all culled (the plane too: 5 cm above it).
  tool.X_W.translation() = Vector3(0, 0, 0.05);
  const ContactSummary& high = contact.Compute(tool);
  EXPECT_EQ(high.num_candidates, 0);
  EXPECT_EQ(high.num_culled, 3);
  // Pressing into the table: the table is a candidate; the floor (12 mm
  // below the tool, margin 5 mm) and the ball a metre away are not.
  for (int i = 0; i < 20; ++i) {
    tool.X_W.translation() = Vector3(0, 0, 0.0105 - 0.0002 * i);
    contact.Compute(tool);
  }
  const ContactSummary& pressed = contact.Compute(tool);
  EXPECT_EQ(pressed.num_candidates, 1);
  EXPECT_EQ(pressed.num_culled, 2);
  EXPECT_EQ(pressed.num_in_contact, 1);
  EXPECT_TRUE(contact.last_result(0).in_collision);
  // Lifted out of reach: culled, its last answer cleared, and the next
  // contact starts cold (no motion-coherence start).
  tool.X_W.translation() = Vector3(0, 0, 0.05);
  contact.Compute(tool);  // swept box still reaches down
  contact.Compute(tool);
  EXPECT_EQ(contact.Compute(tool).num_candidates, 0);
  EXPECT_FALSE(contact.last_result(0).in_collision);
  tool.X_W.translation() = Vector3(0, 0, 0.008);
  contact.Compute(tool);
  EXPECT_TRUE(contact.last_result(0).in_collision);
  EXPECT_NE(contact.last_result(0).initializer, pd::Initializer::kMotionCoherence);
}

// The many-objects scene: pressing on the centre block queries it alone (the
// other 81 are culled), gives the same wrench as box_on_box, and no tick
// allocates once warm.
TEST(BroadPhase, ManyObjectsSceneQueriesOnlyTheObjectInReachWithoutAllocating) {
  const SceneConfig many = LoadSceneConfig(test::ConfigDir() + "/many_objects.yaml");
  const SceneConfig one = LoadSceneConfig(test::ConfigDir() + "/box_on_box.yaml");
  ASSERT_GE(many.objects.size(), 50u);
  const SceneModels many_models = BuildSceneModels(many);
  // Identical meshes (11 prisms, 11 cups, 11 tori) are built once each.
  std::set<const pd::Geometry*> meshes;
  int mesh_objects = 0;
  for (const SceneObject& o : many_models.objects) {
    if (!o.geometry->model()) continue;
    ++mesh_objects;
    meshes.insert(o.geometry.get());
  }
  EXPECT_GT(mesh_objects, 30);
  EXPECT_EQ(meshes.size(), 3u);
  PenaltyContact crowd(many_models, many.contact);
  PenaltyContact single(BuildSceneModels(one), one.contact);
  RigidState tool;
  auto press = [&](int i) {
    const double s = 0.5 - 0.5 * std::cos(0.01 * i);  // down and up, 0 to 1 cm deep
    tool.X_W.translation() = Vector3(0.005 * std::sin(0.003 * i), -0.003, 0.012 - 0.012 * s);
    tool.v_W = Vector3::Zero();
  };
  for (int i = 0; i < 400; ++i) {  // warm up: solvers' scratch grows
    press(i);
    crowd.Compute(tool);
    single.Compute(tool);
  }
  const int64_t before = test::ThreadAllocations();
  int max_candidates = 0;
  for (int i = 400; i < 1200; ++i) {
    press(i);
    const ContactSummary& c = crowd.Compute(tool);
    const ContactSummary& s = single.Compute(tool);
    max_candidates = std::max(max_candidates, c.num_candidates);
    EXPECT_EQ(c.num_candidates + c.num_culled, static_cast<int>(many.objects.size()));
    EXPECT_LT((c.wrench.w0.f_W - s.wrench.w0.f_W).norm(), 1e-9 + 1e-9 * s.wrench.w0.f_W.norm()) << i;
  }
  EXPECT_EQ(test::ThreadAllocations() - before, 0);
  EXPECT_EQ(max_candidates, 1);
}

}  // namespace
}  // namespace haptics
