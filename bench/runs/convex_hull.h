#pragma once
// 3D convex hull by quickhull, for the FCL GJK/EPA baseline (fcl::Convex wants
// the hull's vertices and faces; giving it every mesh vertex would make its
// support function scan the whole mesh).
#include <Eigen/Core>
#include <vector>

#include "pd_core/geometry/pose.h"

namespace pd_bench {

struct ConvexHull {
  std::vector<pd::Vector3> vertices;          // subset of the input points (m)
  std::vector<Eigen::Vector3i> triangles;     // counter-clockwise seen from outside
  bool consistent = true;  // every edge shared by exactly two faces
};

// Throws std::invalid_argument for fewer than 4 points or a flat point set.
ConvexHull ComputeConvexHull(const std::vector<pd::Vector3>& points);

}  // namespace pd_bench
