#include "bench/runs/fcl_baselines.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "bench/runs/convex_hull.h"

namespace pd_bench {
namespace {

using Clock = std::chrono::steady_clock;

std::shared_ptr<fcl::Convexd> MakeConvex(const pd::TriangleMesh& mesh, int* num_vertices,
                                         bool* consistent) {
  const ConvexHull hull = ComputeConvexHull(mesh.vertices);
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>(hull.vertices);
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(4 * hull.triangles.size());
  for (const Eigen::Vector3i& t : hull.triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
  *num_vertices = static_cast<int>(hull.vertices.size());
  *consistent = hull.consistent;
  return std::make_shared<fcl::Convexd>(vertices, static_cast<int>(hull.triangles.size()), faces);
}

template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> MakeBvh(const pd::TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  std::vector<fcl::Triangle> tris;
  tris.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) tris.emplace_back(t[0], t[1], t[2]);
  model->beginModel(mesh.num_triangles(), mesh.num_vertices());
  model->addSubModel(mesh.vertices, tris);
  model->endModel();
  return model;
}

double MicrosSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

}  // namespace

struct FclBaselines::Impl {
  std::shared_ptr<fcl::Convexd> probe_hull, scene_hull;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> probe_bvh, scene_bvh;
  std::shared_ptr<fcl::BVHModel<fcl::OBBd>> probe_obb, scene_obb;
  int probe_hull_vertices = 0, scene_hull_vertices = 0;
  bool consistent = true;
  int max_contacts = 1;
  double build_ms = 0.0;
};

FclBaselines::FclBaselines(const pd::TriangleMesh& probe, const pd::TriangleMesh& scene,
                           int max_contacts)
    : impl_(std::make_unique<Impl>()) {
  const auto t0 = Clock::now();
  bool c1 = true, c2 = true;
  impl_->probe_hull = MakeConvex(probe, &impl_->probe_hull_vertices, &c1);
  impl_->scene_hull = MakeConvex(scene, &impl_->scene_hull_vertices, &c2);
  impl_->consistent = c1 && c2;
  impl_->probe_bvh = MakeBvh<fcl::OBBRSSd>(probe);
  impl_->scene_bvh = MakeBvh<fcl::OBBRSSd>(scene);
  impl_->probe_obb = MakeBvh<fcl::OBBd>(probe);
  impl_->scene_obb = MakeBvh<fcl::OBBd>(scene);
  impl_->max_contacts = std::max(1, max_contacts);

  impl_->build_ms = MicrosSince(t0) / 1000.0;
}

FclBaselines::~FclBaselines() = default;

FclAnswer FclBaselines::ConvexHullPd(const pd::Isometry3& X_WP, const pd::Isometry3& X_WS) const {
  // Signed distance through libccd (GJK, then EPA when penetrating). The
  // collide() contact depths are worse in FCL 0.7: GST_LIBCCD answers with
  // MPR (not the minimum translation) and GST_INDEP's EPA stops unconverged
  // on hulls of a few hundred vertices (checked against a support-function
  // brute force).
  fcl::DistanceRequestd request;
  request.enable_signed_distance = true;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::DistanceResultd result;
  const auto t0 = Clock::now();
  fcl::distance(impl_->probe_hull.get(), X_WP, impl_->scene_hull.get(), X_WS, request, result);
  FclAnswer a;
  a.time_us = MicrosSince(t0);
  a.in_collision = result.min_distance < 0;
  a.depth = std::max(0.0, -result.min_distance);
  return a;
}

FclAnswer FclBaselines::MeshContactPd(const pd::Isometry3& X_WP, const pd::Isometry3& X_WS) const {
  fcl::CollisionRequestd request(impl_->max_contacts, true);
  fcl::CollisionResultd result;
  const auto t0 = Clock::now();
  fcl::collide(impl_->probe_bvh.get(), X_WP, impl_->scene_bvh.get(), X_WS, request, result);
  FclAnswer a;
  a.time_us = MicrosSince(t0);
  a.in_collision = result.isCollision();
  a.num_contacts = static_cast<int>(result.numContacts());
  for (size_t i = 0; i < result.numContacts(); ++i)
    a.depth = std::max(a.depth, result.getContact(i).penetration_depth);
  return a;
}

FclAnswer FclBaselines::Collide(const pd::Isometry3& X_WP, const pd::Isometry3& X_WS) const {
  // OBB, not OBBRSS: FCL's OBBRSS/RSS boolean collide is 100x slower (shared/README.md).
  fcl::CollisionRequestd request(1, false);
  fcl::CollisionResultd result;
  const auto t0 = Clock::now();
  fcl::collide(impl_->probe_obb.get(), X_WP, impl_->scene_obb.get(), X_WS, request, result);
  FclAnswer a;
  a.time_us = MicrosSince(t0);
  a.in_collision = result.isCollision();
  return a;
}

int FclBaselines::probe_hull_vertices() const { return impl_->probe_hull_vertices; }
int FclBaselines::scene_hull_vertices() const { return impl_->scene_hull_vertices; }
bool FclBaselines::hulls_consistent() const { return impl_->consistent; }
double FclBaselines::build_ms() const { return impl_->build_ms; }

}  // namespace pd_bench
