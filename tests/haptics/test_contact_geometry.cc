// ContactGeometry on a real mesh scene (CGAL knot1 at 5 cm on the refined
// elephant, 89k triangles; bench/scenes/knot_tool_elephant_bunny_164k.yaml
// without the bunny): a pair's warm start is cheap over small motions and
// costs no more than a cold query after a jump of the tool. Before, the warm
// query after a jump built a leaf-pair list covering the jump: the query
// after a 3 mm jump cost 890k tests against 115k cold, and on the geometry
// thread each slow answer let the tool jump further (the contact model went
// seconds stale on that scene). Work is counted in box and triangle tests
// (deterministic), not time. On the geometry thread (GeometryWorker) the
// queries answer first and the worker rebuilds their candidate lists after
// publishing the answer (PolyDepthOptions::defer_list_builds).
#include "haptics/contact/contact_geometry.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "haptics/contact/geometry_thread.h"
#include "haptics/haptic_renderer.h"
#include "haptics/scene/build_scene.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics_test_util.h"
#include "tests/prerequisites.h"

namespace haptics {
namespace {

const std::string kScene = test::BenchSceneDir() + "/knot_tool_elephant_bunny_164k.yaml";
const std::string kMeshDir = test::MeshDir();

int64_t Work(const pd::PenetrationResult& r) { return r.box_tests + r.triangle_tests; }

Isometry3 ToolPose(const Vector3& p_WT, double tilt_rad = 0.0) {
  Isometry3 X = Isometry3::Identity();
  X.translation() = p_WT;
  X.linear() = Eigen::AngleAxisd(tilt_rad, Vector3::UnitX()).toRotationMatrix();
  return X;
}

TEST(ContactGeometry, WarmQueriesAreCheapOverSmallMotionsAndNoDearerThanColdAfterAJump) {
  PD_REQUIRE_FILE(kMeshDir + "/refined_elephant.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/knot1.off", "run scripts/fetch_meshes.sh");
  SceneConfig config = LoadSceneConfig(kScene);
  ASSERT_EQ(config.objects[0].name, "elephant");
  config.objects.resize(1);
  const SceneModels models = BuildSceneModels(config);
  // Unbounded queries (no time budget): the work of each is deterministic.
  ContactGeometry geometry(models.tool, models.X_TG, models.objects, config.contact);
  ASSERT_EQ(geometry.solver(0).method(), pd::PdMethod::kPolyDepth);
  ContactSnapshot answer;
  answer.Reserve(geometry.num_objects());

  // About 1 mm into the elephant's back, then sliding 0.05 mm per query.
  const Vector3 p_A(-0.024, -0.004, 0.0185);
  geometry.Query(ToolPose(p_A), 1, &answer);
  ASSERT_TRUE(geometry.last_result(0).in_collision);
  const int64_t cold_A = Work(geometry.last_result(0));
  int64_t warm_max = 0;
  for (int k = 1; k <= 5; ++k) {
    geometry.Query(ToolPose(p_A + Vector3(0, 5e-5 * k, 0)), 1 + k, &answer);
    ASSERT_TRUE(geometry.last_result(0).valid);
    warm_max = std::max(warm_max, Work(geometry.last_result(0)));
  }
  // Small motions stay warm, and warm is what makes them cheap.
  EXPECT_LT(warm_max, cold_A / 5) << "cold " << cold_A;

  // A 3 mm jump with a 3 degree turn (an answer that took long): this query
  // costs no more than a cold one at the same pose.
  const Isometry3 X_B = ToolPose(p_A + Vector3(0, 3e-3, 0), 3.0 * M_PI / 180.0);
  geometry.Query(X_B, 10, &answer);
  const pd::PenetrationResult after_jump = geometry.last_result(0);
  geometry.ResetWarmStarts();
  geometry.Query(X_B, 11, &answer);
  const pd::PenetrationResult cold = geometry.last_result(0);
  ASSERT_TRUE(cold.in_collision);
  ASSERT_TRUE(after_jump.in_collision);
  EXPECT_TRUE(after_jump.valid);
  EXPECT_LE(Work(after_jump), Work(cold) * 11 / 10) << "cold " << Work(cold);
  EXPECT_EQ(after_jump.initializer, pd::Initializer::kMotionCoherence);
  EXPECT_NEAR(after_jump.depth, cold.depth, 1e-2 * cold.depth);
}


TEST(ContactGeometry, TheWorkerRebuildsListsAfterPublishingTheAnswer) {
  PD_REQUIRE_FILE(kMeshDir + "/refined_elephant.off", "run scripts/fetch_meshes.sh");
  PD_REQUIRE_FILE(kMeshDir + "/knot1.off", "run scripts/fetch_meshes.sh");
  SceneConfig config = LoadSceneConfig(kScene);
  config.objects.resize(1);
  config.contact.geometry_thread = GeometryThreadMode::kOn;
  const SceneModels models = BuildSceneModels(config);
  // The renderer's geometry defers its list builds when it runs on the thread.
  HapticRenderer renderer(config, models);
  ASSERT_EQ(renderer.geometry().solver(0).method(), pd::PdMethod::kPolyDepth);
  EXPECT_TRUE(renderer.geometry().solver(0).options().defer_list_builds);
  SceneConfig in_tick = config;
  in_tick.contact.geometry_thread = GeometryThreadMode::kOff;
  HapticRenderer sync(in_tick, models);
  EXPECT_FALSE(sync.geometry().solver(0).options().defer_list_builds);

  pd::PolyDepthOptions options;
  options.defer_list_builds = true;
  ContactGeometry geometry(models.tool, models.X_TG, models.objects, config.contact, options);
  GeometryWorker worker(&geometry);
  // 1 mm into the elephant's back, sliding 0.1 mm per pose.
  const Vector3 p_A(-0.024, -0.004, 0.0185);
  int contacts = 0;
  for (int k = 0; k < 60; ++k) {
    worker.Post(ToolPose(p_A + Vector3(0, 1e-4 * k, 0)), k + 1);
    ASSERT_TRUE(worker.RunOnce());
    const pd::PenetrationResult& r = geometry.last_result(0);
    contacts += r.in_collision;
    EXPECT_EQ(r.list_builds, 0) << "pose " << k;  // none before the answer
    // Nothing was posted during the preparation: it ran to the end.
    EXPECT_TRUE(geometry.PrepareNext([] { return true; })) << "pose " << k;
    EXPECT_TRUE(worker.idle());
  }
  EXPECT_GT(contacts, 50);
  // The lists the worker built are in use: the same slide without any
  // preparation costs more.
  ContactGeometry unprepared(models.tool, models.X_TG, models.objects, config.contact, options);
  ContactGeometry prepared(models.tool, models.X_TG, models.objects, config.contact, options);
  ContactSnapshot answer;
  answer.Reserve(1);
  int64_t work_unprepared = 0, work_prepared = 0;
  for (int k = 0; k < 60; ++k) {
    const Isometry3 X = ToolPose(p_A + Vector3(0, 1e-4 * k, 0));
    unprepared.Query(X, k + 1, &answer);
    prepared.Query(X, k + 1, &answer);
    prepared.PrepareNext();
    work_unprepared += Work(unprepared.last_result(0));
    work_prepared += Work(prepared.last_result(0));
    EXPECT_NEAR(prepared.last_result(0).depth, unprepared.last_result(0).depth, 1e-12);
  }
  EXPECT_LT(work_prepared, work_unprepared);
}

}  // namespace
}  // namespace haptics
