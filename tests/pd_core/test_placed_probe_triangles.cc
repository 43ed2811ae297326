// The per-query table of probe triangles placed in S
// (pd_core/proximity/placed_probe_triangles.h): whatever the order of the
// requests, including indices that share a slot, it returns each triangle's
// own vertices and normal, as transforming it afresh does.
#include <gtest/gtest.h>

#include <random>

#include "pd_core/proximity/placed_probe_triangles.h"
#include "tests/pd_core/brute_force_pairs.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

TEST(PlacedProbeTriangles, EveryRequestGetsItsOwnTriangleWhateverShareASlot) {
  const std::string path = std::string(PD_TEST_MESH_DIR) + "/cow.off";
  PD_REQUIRE_FILE(path, "run scripts/fetch_meshes.sh");
  const auto probe = test::LoadCentredModel(path);
  const auto scene = test::LoadCentredModel(path);
  Isometry3 X_WP = Isometry3::Identity();
  X_WP.linear() = Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  X_WP.translation() = Vector3(0.01, -0.02, 0.03);
  const ModelPair pair(*probe, *scene, X_WP, Isometry3::Identity());
  const Vector3 offset_S(1e-3, 2e-3, -5e-4);
  PlacedProbeTriangles placed(pair, offset_S);
  std::mt19937 rng(3);
  const int n = probe->mesh().num_triangles();
  int checked = 0;
  for (int k = 0; k < 2000; ++k) {
    // Runs of indices 32 apart (one slot) mixed with random ones.
    const int t = k % 3 == 0 ? static_cast<int>(rng() % n) : (k * 32 + k % 2) % n;
    const PlacedProbeTriangles::Triangle& got = placed(t);
    Vector3 p[3];
    pair.ProbeTriangle(t, offset_S, p);
    ASSERT_EQ(got.t, t);
    for (int i = 0; i < 3; ++i) ASSERT_EQ(got.p[i], p[i]) << "triangle " << t;
    const Vector3 n_S = pair.X_SP.R_SP * probe->face_normals()[t];
    ASSERT_EQ(got.n, n_S);
    ++checked;
  }
  EXPECT_EQ(checked, 2000);
}

}  // namespace
}  // namespace pd
