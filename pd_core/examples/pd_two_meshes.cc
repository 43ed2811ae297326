// pd_core in one page: load two meshes, then lower the first (the probe P)
// onto the second (the scene S) and print the penetration depth (PD) at each
// step. PD is the shortest translation that separates P from S.
//   pd_two_meshes PROBE_MESH SCENE_MESH [SCALE]    (SCALE: file units -> m)
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "pd_core/mesh/collision_model.h"
#include "pd_core/mesh/load_mesh.h"
#include "pd_core/polydepth/polydepth.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s PROBE_MESH SCENE_MESH [SCALE]\n", argv[0]);
    return 2;
  }
  pd::MeshLoadOptions load;
  load.scale = argc > 3 ? std::atof(argv[3]) : 1.0;
  try {
    // A CollisionModel holds the BVH and everything else a query needs.
    auto probe = pd::CollisionModel::Build(pd::LoadMesh(argv[1], load).mesh);
    auto scene = pd::CollisionModel::Build(pd::LoadMesh(argv[2], load).mesh);
    const pd::MeshBounds b_P = pd::ComputeBounds(probe->mesh());
    const pd::MeshBounds b_S = pd::ComputeBounds(scene->mesh());
    const double height_P = b_P.max.z() - b_P.min.z();

    pd::PolyDepthSolver solver(probe, scene);  // one solver per pair: it keeps the warm start
    const pd::Isometry3 X_WS = pd::Isometry3::Identity();
    std::printf("overlap_m,collision,depth_m,normal_x,normal_y,normal_z,regions,time_us\n");
    // From 10% of P's height above S's top down to 50% of it inside S,
    // P centred over S in x and y.
    for (int i = -2; i <= 10; ++i) {
      const double overlap = 0.05 * i * height_P;
      pd::Vector3 p_WP = b_S.center() - b_P.center();
      p_WP.z() = b_S.max.z() - b_P.min.z() - overlap;
      const pd::Isometry3 X_WP = pd::MakePose(p_WP, 1, 0, 0, 0);
      // coherent = true: start from the previous step's answer (motion coherence).
      const pd::PenetrationResult r = solver.Solve(X_WP, X_WS, /*coherent=*/true);
      std::printf("%.6f,%d,%.6f,%.4f,%.4f,%.4f,%d,%.1f\n", overlap, r.in_collision ? 1 : 0,
                  r.depth, r.normal_W.x(), r.normal_W.y(), r.normal_W.z(), r.num_regions,
                  r.time_us);
    }
  } catch (const std::exception& e) {  // pd::MeshLoadError names the file
    std::fprintf(stderr, "pd_two_meshes: %s\n", e.what());
    return 1;
  }
  return 0;
}
