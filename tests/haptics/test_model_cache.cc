// The disk cache of mesh precomputation (pd_core/mesh/model_cache.h): a cached
// model equals a freshly built one field by field and gives the same PD
// answers; corrupt, truncated or foreign files are detected and rebuilt; the
// key follows the mesh content.
#include "pd_core/mesh/model_cache.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "haptics/scene/build_scene.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics_test_util.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/polydepth/polydepth.h"

namespace haptics {
namespace {

namespace fs = std::filesystem;

template <typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void ExpectSameModel(const pd::CollisionModel& a, const pd::CollisionModel& b) {
  EXPECT_TRUE(SameBytes(a.mesh().vertices, b.mesh().vertices));
  EXPECT_TRUE(SameBytes(a.mesh().triangles, b.mesh().triangles));
  EXPECT_EQ(a.mesh().name, b.mesh().name);
  EXPECT_TRUE(SameBytes(a.topology().edges, b.topology().edges));
  EXPECT_TRUE(SameBytes(a.topology().triangle_edges, b.topology().triangle_edges));
  EXPECT_EQ(a.closed(), b.closed());
  EXPECT_TRUE(SameBytes(a.bvh().nodes(), b.bvh().nodes()));
  EXPECT_TRUE(SameBytes(a.bvh().order(), b.bvh().order()));
  EXPECT_EQ(a.bvh().depth(), b.bvh().depth());
  EXPECT_TRUE(SameBytes(a.face_normals(), b.face_normals()));
  EXPECT_EQ(a.center(), b.center());
  EXPECT_EQ(a.radius(), b.radius());
  EXPECT_EQ(a.centroid(), b.centroid());
  EXPECT_TRUE(SameBytes(a.support_directions(), b.support_directions()));
  EXPECT_TRUE(SameBytes(a.support_values(), b.support_values()));
  EXPECT_TRUE(SameBytes(a.hull_vertices(), b.hull_vertices()));
  EXPECT_TRUE(SameBytes(a.owned_features(), b.owned_features()));
  EXPECT_TRUE(SameBytes(a.component_vertices(), b.component_vertices()));
  EXPECT_TRUE(SameBytes(a.inner_spheres(), b.inner_spheres()));
  EXPECT_EQ(a.inner_spheres().empty(), !a.closed());  // the torus is closed: it has some
}

class ModelCacheTest : public ::testing::Test {
 protected:
  static pd::TriangleMesh Torus() { return pd::MakeTorus(0.03, 0.01, 24, 12); }

  std::shared_ptr<const pd::CollisionModel> Cached(pd::TriangleMesh mesh, pd::ModelCacheReport* r) {
    return pd::BuildCollisionModelCached(std::move(mesh), dir_.string(), r);
  }

  pd::test::ScopedTempDir tmp_{"haptics_test_model_cache"};
  const fs::path dir_ = tmp_.path();
};

TEST_F(ModelCacheTest, CachedModelEqualsTheFreshlyBuiltOneAndGivesTheSameAnswers) {
  const auto fresh = pd::CollisionModel::Build(Torus());
  pd::ModelCacheReport first, second;
  const auto built = Cached(Torus(), &first);
  EXPECT_EQ(first.outcome, pd::ModelCacheOutcome::kMiss);
  EXPECT_TRUE(first.problem.empty()) << first.problem;
  ASSERT_TRUE(fs::is_regular_file(first.path));
  const auto loaded = Cached(Torus(), &second);
  EXPECT_EQ(second.outcome, pd::ModelCacheOutcome::kHit);
  EXPECT_EQ(second.path, first.path);
  ExpectSameModel(*fresh, *built);
  ExpectSameModel(*fresh, *loaded);

  // Same PD answers, cold and warm, for a probe against either scene model.
  const auto probe = pd::CollisionModel::Build(pd::MakeIcosphere(0.012, 2));
  pd::PolyDepthSolver from_fresh(probe, fresh), from_cache(probe, loaded);
  for (int i = 0; i < 20; ++i) {
    const double a = 0.3 * i;
    const pd::Isometry3 X_WP =
        pd::MakePose(pd::Vector3(0.03 * std::cos(a), 0.03 * std::sin(a), 0.004 * std::sin(3 * a)), 1, 0, 0, 0);
    const pd::PenetrationResult r1 = from_fresh.Solve(X_WP, pd::Isometry3::Identity(), i > 0);
    const pd::PenetrationResult r2 = from_cache.Solve(X_WP, pd::Isometry3::Identity(), i > 0);
    ASSERT_TRUE(r1.in_collision) << i;
    EXPECT_EQ(r1.in_collision, r2.in_collision);
    EXPECT_EQ(r1.valid, r2.valid);
    EXPECT_EQ(r1.depth, r2.depth) << i;
    EXPECT_EQ(r1.translation_W, r2.translation_W) << i;
    EXPECT_EQ(r1.num_regions, r2.num_regions) << i;
  }
}

TEST_F(ModelCacheTest, CorruptTruncatedOrForeignFilesAreRejectedAndRebuilt) {
  pd::ModelCacheReport report;
  const auto fresh = pd::CollisionModel::Build(Torus());
  Cached(Torus(), &report);
  const std::string path = report.path;
  const auto size = fs::file_size(path);

  auto rewrite = [&](const std::function<void(std::string&)>& damage) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    damage(bytes);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  };
  struct Case {
    const char* name;
    std::function<void(std::string&)> damage;
    const char* problem;
  };
  const Case cases[] = {
      {"flipped byte", [&](std::string& b) { b[size / 2] ^= 0x5a; }, "checksum"},
      {"truncated", [&](std::string& b) { b.resize(size - 100); }, "size mismatch"},
      {"header only", [&](std::string& b) { b.resize(10); }, "truncated header"},
      {"other magic", [&](std::string& b) { b[0] = 'X'; }, "bad magic"},
      {"other version", [&](std::string& b) { b[8] = 99; }, "format version"},
      {"empty", [&](std::string& b) { b.clear(); }, "truncated header"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    rewrite(c.damage);
    pd::ModelCacheReport rejected;
    const auto model = Cached(Torus(), &rejected);
    EXPECT_EQ(rejected.outcome, pd::ModelCacheOutcome::kRejected);
    EXPECT_NE(rejected.problem.find(path), std::string::npos) << rejected.problem;
    EXPECT_NE(rejected.problem.find(c.problem), std::string::npos) << rejected.problem;
    EXPECT_NE(rejected.problem.find("rebuilt"), std::string::npos) << rejected.problem;
    ExpectSameModel(*fresh, *model);
    // Rewritten: the next load is a hit again.
    pd::ModelCacheReport again;
    Cached(Torus(), &again);
    EXPECT_EQ(again.outcome, pd::ModelCacheOutcome::kHit);
    EXPECT_EQ(fs::file_size(path), size);
  }
}

TEST_F(ModelCacheTest, AValidFileOfAnotherMeshUnderThisKeyIsNotTrusted) {
  // Another mesh's (valid, checksummed) file copied under this mesh's name:
  // a key collision, as far as the cache can tell.
  pd::ModelCacheReport mine, other;
  Cached(Torus(), &mine);
  Cached(pd::MakeTorus(0.03, 0.011, 24, 12), &other);  // same counts, other vertices
  fs::copy_file(other.path, mine.path, fs::copy_options::overwrite_existing);
  pd::ModelCacheReport report;
  const auto model = Cached(Torus(), &report);
  EXPECT_EQ(report.outcome, pd::ModelCacheOutcome::kRejected);
  EXPECT_NE(report.problem.find("differs"), std::string::npos) << report.problem;
  ExpectSameModel(*pd::CollisionModel::Build(Torus()), *model);
}

TEST_F(ModelCacheTest, KeyFollowsTheMeshContent) {
  const pd::TriangleMesh a = Torus();
  pd::TriangleMesh moved = a;
  moved.vertices[7].x() += 1e-12;
  pd::TriangleMesh reordered = a;
  std::swap(reordered.triangles[0], reordered.triangles[1]);
  pd::TriangleMesh renamed = a;
  renamed.name = "another name";
  EXPECT_EQ(pd::ModelCacheKey(a), pd::ModelCacheKey(Torus()));
  EXPECT_EQ(pd::ModelCacheKey(a), pd::ModelCacheKey(renamed));  // content only
  EXPECT_NE(pd::ModelCacheKey(a), pd::ModelCacheKey(moved));
  EXPECT_NE(pd::ModelCacheKey(a), pd::ModelCacheKey(reordered));
  EXPECT_NE(pd::ModelCacheKey(a), pd::ModelCacheKey(pd::MakeTorus(0.03, 0.01, 24, 13)));
  // A different mesh gets its own file; the first stays a hit.
  pd::ModelCacheReport r1, r2, r3;
  Cached(a, &r1);
  Cached(moved, &r2);
  Cached(a, &r3);
  EXPECT_NE(r1.path, r2.path);
  EXPECT_EQ(r2.outcome, pd::ModelCacheOutcome::kMiss);
  EXPECT_EQ(r3.outcome, pd::ModelCacheOutcome::kHit);
}

TEST_F(ModelCacheTest, NoDirectoryMeansNoCacheAndAnUnwritableOneIsReported) {
  pd::ModelCacheReport none;
  const auto model = pd::BuildCollisionModelCached(Torus(), "", &none);
  EXPECT_EQ(none.outcome, pd::ModelCacheOutcome::kDisabled);
  EXPECT_TRUE(none.path.empty());
  ASSERT_NE(model, nullptr);
  // A regular file where the directory should be: built, problem reported.
  const fs::path blocker = dir_ / "not_a_dir";
  test::WriteFile(blocker, "x");
  pd::ModelCacheReport report;
  const auto built = pd::BuildCollisionModelCached(Torus(), (blocker / "cache").string(), &report);
  ASSERT_NE(built, nullptr);
  EXPECT_EQ(report.outcome, pd::ModelCacheOutcome::kMiss);
  EXPECT_NE(report.problem.find("cannot"), std::string::npos) << report.problem;
}

TEST_F(ModelCacheTest, SceneBuildUsesTheCacheDirectory) {
  // spoon_in_cup has two meshes (spoon tool, cup): both cached, then hit.
  SceneConfig config = LoadSceneConfig(test::ConfigDir() + "/spoon_in_cup.yaml");
  config.cache_dir = (dir_ / "scene_cache").string();
  const SceneModels first = BuildSceneModels(config);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(config.cache_dir)) files += entry.path().extension() == ".pdmodel";
  EXPECT_EQ(files, 2);
  const SceneModels second = BuildSceneModels(config);
  ExpectSameModel(*first.tool->model(), *second.tool->model());
  ExpectSameModel(*first.objects[0].geometry->model(), *second.objects[0].geometry->model());
  // The override argument (the server's --cache-dir) wins over the config.
  const fs::path override_dir = dir_ / "override";
  BuildSceneModels(config, override_dir.string());
  EXPECT_TRUE(fs::is_directory(override_dir));
}

}  // namespace
}  // namespace haptics
