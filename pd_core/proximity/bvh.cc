#include "pd_core/proximity/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace pd {

Bvh::Bvh(const TriangleMesh& mesh) {
  const int n = mesh.num_triangles();
  if (n == 0) return;
  std::vector<BuildTriangle> tris(n);
  for (int t = 0; t < n; ++t) {
    const auto& tri = mesh.triangles[t];
    const Vector3& a = mesh.vertices[tri[0]];
    const Vector3& b = mesh.vertices[tri[1]];
    const Vector3& c = mesh.vertices[tri[2]];
    tris[t] = {{a, b, c}, t};
  }
  nodes_.reserve(2 * n);
  // Cost-chosen splits above this level, equal counts from it on (see Build).
  int log2_n = 0;
  while ((1 << log2_n) < n) ++log2_n;
  cost_split_levels_ = 2 * log2_n;
  Build(tris, 0, n, 1);
  nodes_.shrink_to_fit();
  order_.resize(n);
  for (int i = 0; i < n; ++i) order_[i] = tris[i].t;
  DeriveBounds(&nodes_);
}

int Bvh::MeasureDepth(const std::vector<BvhNode>& nodes) {
  if (nodes.empty()) return 0;
  // Children always follow their parent (left = i + 1, right > i), so one
  // forward pass assigns every node its level.
  std::vector<int> level(nodes.size(), 0);
  level[0] = 1;
  int depth = 1;
  for (size_t i = 0; i < nodes.size(); ++i) {
    depth = std::max(depth, level[i]);
    if (nodes[i].is_leaf()) continue;
    level[i + 1] = level[i] + 1;
    level[nodes[i].right_or_first] = level[i] + 1;
  }
  return depth;
}

Bvh Bvh::FromNodes(std::vector<BvhNode> nodes, std::vector<int32_t> order) {
  Bvh bvh;
  bvh.nodes_ = std::move(nodes);
  bvh.order_ = std::move(order);
  bvh.depth_ = MeasureDepth(bvh.nodes_);
  DeriveBounds(&bvh.nodes_);
  return bvh;
}

namespace {

// The float nearest x from above (a bound stays a bound).
float RoundUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Surface area (over 2) of the axis-aligned box [lo, hi].
double BoxArea(const Vector3& lo, const Vector3& hi) {
  const Vector3 e = hi - lo;
  return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

}  // namespace

void Bvh::DeriveBounds(std::vector<BvhNode>* nodes) {
  for (BvhNode& n : *nodes) {
    const Vector3 aabb = n.R_MB.cwiseAbs() * n.half_B;
    for (int i = 0; i < 3; ++i) n.aabb_half_M[i] = RoundUp(aabb[i]);
    n.radius = RoundUp(n.half_B.norm());
  }
}

// Top-down, O(n log n). A node is split where the two children's bounds
// cost least, each child's surface area times its triangle count (the
// surface-area heuristic, on 16 bins of the centroids along their longest
// axis; binning all three axes did 0-7% less work for up to 25% more build
// time): the cut falls in the gaps between groups of triangles, not at
// equal counts. A pair descent tests a node pair when their boxes are near,
// which a smaller surface makes rarer. On the benchmark's meshes, against
// equal counts: same answers; warm haptic work -22-34% at the median and
// -20-31% at p99; cold queries' box tests -27-46% and triangle tests
// -27-65%; 4-12% fewer nodes (2-5% more on camel and bunny00); model builds
// within about 10% of before (timing noise here is as large). A cost-chosen split can be lopsided, so from level
// cost_split_levels_ (twice the balanced depth) on the splits are into
// equal counts: the depth stays within about three times the balanced one,
// well inside the descents' fixed stacks.
int Bvh::Build(std::vector<BuildTriangle>& tris, int begin, int end, int level) {
  depth_ = std::max(depth_, level);
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  // Box axes: principal directions of the vertices' scatter (edge-based
  // for a single triangle, where the scatter is flat and exact), or the
  // mesh frame's own axes where those give the smaller box (faces and edges
  // aligned with them, as on CAD parts: fandisk's warm queries ~25% fewer
  // tests).
  // The scatter in one pass, about a vertex of the node (shifted sums: no
  // cancellation from the mesh frame's origin being far away).
  const Vector3 shift = tris[begin].v[0];
  Vector3 sum = Vector3::Zero();
  Matrix3 sum2 = Matrix3::Zero();
  Vector3 clo = Vector3::Constant(1e300), chi = Vector3::Constant(-1e300);
  Vector3 lo_M = Vector3::Constant(1e300), hi_M = Vector3::Constant(-1e300);
  for (int i = begin; i < end; ++i) {
    const BuildTriangle& b = tris[i];
    for (int k = 0; k < 3; ++k) {
      const Vector3 d = b.v[k] - shift;
      sum += d;
      sum2 += d * d.transpose();
    }
    lo_M = lo_M.cwiseMin(b.lo());
    hi_M = hi_M.cwiseMax(b.hi());
    const Vector3 c = b.centroid();
    clo = clo.cwiseMin(c);
    chi = chi.cwiseMax(c);
  }
  const double num_vertices = 3.0 * (end - begin);
  const Matrix3 scatter = sum2 - sum * sum.transpose() / num_vertices;
  Matrix3 R = Matrix3::Identity();
  Eigen::SelfAdjointEigenSolver<Matrix3> eig;
  eig.computeDirect(scatter);
  if (eig.info() == Eigen::Success && eig.eigenvectors().allFinite()) {
    R = eig.eigenvectors();
    // Re-orthonormalise (computeDirect is accurate to ~1e-8 on flat input).
    R.col(0).normalize();
    R.col(1) = (R.col(1) - R.col(1).dot(R.col(0)) * R.col(0)).normalized();
    R.col(2) = R.col(0).cross(R.col(1));
    if (!R.allFinite()) R = Matrix3::Identity();
  }
  Vector3 lo = Vector3::Constant(1e300), hi = Vector3::Constant(-1e300);
  for (int i = begin; i < end; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Vector3 p_B = R.transpose() * tris[i].v[k];
      lo = lo.cwiseMin(p_B);
      hi = hi.cwiseMax(p_B);
    }
  }
  if (BoxArea(lo_M, hi_M) < BoxArea(lo, hi)) {
    R = Matrix3::Identity();
    lo = lo_M;
    hi = hi_M;
  }
  nodes_[index].R_MB = R;
  nodes_[index].center_M = R * (0.5 * (lo + hi));
  nodes_[index].half_B = 0.5 * (hi - lo);
  if (end - begin <= kMaxLeafTriangles) {
    nodes_[index].right_or_first = begin;  // order_ is filled from tris at the end
    nodes_[index].count = end - begin;
    return index;
  }
  // The split: the cheapest boundary between bins along the longest axis of
  // the centroids' bounds, or none (all in one bin, or deep in the tree).
  constexpr int kBins = 16;
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const double extent = chi[axis] - clo[axis];
  double split = 0.0;
  bool cost_split = false;
  if (level < cost_split_levels_ && extent > 0.0) {
    const double to_bin = kBins / extent;
    std::array<Vector3, kBins> bin_lo, bin_hi;
    std::array<int, kBins> bin_n{};
    bin_lo.fill(Vector3::Constant(1e300));
    bin_hi.fill(Vector3::Constant(-1e300));
    for (int i = begin; i < end; ++i) {
      const BuildTriangle& b = tris[i];
      const int k = std::clamp(static_cast<int>(to_bin * (b.centroid(axis) - clo[axis])), 0, kBins - 1);
      bin_lo[k] = bin_lo[k].cwiseMin(b.lo());
      bin_hi[k] = bin_hi[k].cwiseMax(b.hi());
      ++bin_n[k];
    }
    // Cost of the bins above each boundary, then sweep up from below.
    std::array<double, kBins> above{};
    Vector3 l = Vector3::Constant(1e300), h = Vector3::Constant(-1e300);
    int count = 0;
    for (int k = kBins - 1; k > 0; --k) {
      l = l.cwiseMin(bin_lo[k]);
      h = h.cwiseMax(bin_hi[k]);
      count += bin_n[k];
      above[k] = count > 0 ? BoxArea(l, h) * count : 0.0;
    }
    l = Vector3::Constant(1e300);
    h = Vector3::Constant(-1e300);
    count = 0;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k + 1 < kBins; ++k) {
      l = l.cwiseMin(bin_lo[k]);
      h = h.cwiseMax(bin_hi[k]);
      count += bin_n[k];
      if (count == 0 || count == end - begin) continue;
      const double cost = BoxArea(l, h) * count + above[k + 1];
      if (cost < best) {
        best = cost;
        split = clo[axis] + (k + 1) / to_bin;
        cost_split = true;
      }
    }
  }
  int mid = begin;
  if (cost_split) {
    mid = static_cast<int>(
        std::partition(tris.begin() + begin, tris.begin() + end,
                       [&](const BuildTriangle& b) { return b.centroid(axis) < split; }) -
        tris.begin());
  }
  if (mid == begin || mid == end) {
    mid = (begin + end) / 2;
    std::nth_element(tris.begin() + begin, tris.begin() + mid, tris.begin() + end,
                     [&](const BuildTriangle& a, const BuildTriangle& b) {
                       return a.centroid(axis) < b.centroid(axis);
                     });
  }
  Build(tris, begin, mid, level + 1);
  const int right = Build(tris, mid, end, level + 1);
  nodes_[index].right_or_first = right;
  nodes_[index].count = 0;
  return index;
}

}  // namespace pd
