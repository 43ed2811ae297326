#pragma once
// FCL 0.7 baselines for penetration depth, on the same configurations as
// PolyDepth. This header keeps FCL out of other translation units (its headers
// are slow to compile).
//  - Convex hulls + GJK/EPA (fcl::Convex, signed fcl::distance via libccd):
//    the hulls' PD, an upper bound on the meshes' PD (separating the hulls
//    separates the meshes).
//  - Mesh-mesh contacts (BVHModel<OBBRSS>, enable_contact): the largest
//    per-triangle-pair penetration_depth FCL reports; no global guarantee.
//  - Boolean mesh-mesh collide (BVHModel<OBB>, first contact only): the
//    cost yardstick for a warm PD query, not a PD at all.
#include <memory>

#include "pd_core/mesh/mesh.h"
#include "pd_core/geometry/pose.h"

namespace pd_bench {

struct FclAnswer {
  bool in_collision = false;
  double depth = 0.0;    // m
  double time_us = 0.0;  // wall time of the fcl::collide call
  int num_contacts = 0;
};

class FclBaselines {
 public:
  // max_contacts bounds the mesh-mesh contact list (the depth is a max over it).
  FclBaselines(const pd::TriangleMesh& probe, const pd::TriangleMesh& scene, int max_contacts);
  ~FclBaselines();

  FclAnswer ConvexHullPd(const pd::Isometry3& X_WP, const pd::Isometry3& X_WS) const;
  FclAnswer MeshContactPd(const pd::Isometry3& X_WP, const pd::Isometry3& X_WS) const;
  // Boolean collide only (depth 0); time_us is its wall time.
  FclAnswer Collide(const pd::Isometry3& X_WP, const pd::Isometry3& X_WS) const;

  int probe_hull_vertices() const;
  int scene_hull_vertices() const;
  bool hulls_consistent() const;  // quickhull produced closed 2-manifolds
  double build_ms() const;        // hulls + BVHs

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pd_bench
