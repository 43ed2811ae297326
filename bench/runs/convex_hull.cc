#include "bench/runs/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace pd_bench {
namespace {

using pd::Vector3;

struct Face {
  int v[3];
  Vector3 n;  // unit outward normal
  double d;   // plane offset: n·x = d on the face
  std::vector<int> outside;  // points above this face that no earlier face claimed
  bool alive = true;
};

uint64_t EdgeKey(int a, int b) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

class QuickHull {
 public:
  explicit QuickHull(const std::vector<Vector3>& p) : p_(p) {}

  ConvexHull Run() {
    if (p_.size() < 4) throw std::invalid_argument("convex hull: fewer than 4 points");
    Vector3 lo = p_[0], hi = p_[0];
    for (const Vector3& x : p_) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    // Points closer than this to a plane count as on it (round-off guard).
    eps_ = 1e-10 * std::max((hi - lo).norm(), 1e-300);
    InitialSimplex();
    std::vector<int> all(p_.size());
    for (size_t i = 0; i < p_.size(); ++i) all[i] = static_cast<int>(i);
    Assign(all, 0);
    for (size_t f = 0; f < faces_.size(); ++f) {
      // New faces are appended, so this loop also visits them.
      while (faces_[f].alive && !faces_[f].outside.empty()) AddPoint(f);
    }
    return Collect();
  }

 private:
  double Dist(const Face& f, int i) const { return f.n.dot(p_[i]) - f.d; }

  int MakeFace(int a, int b, int c) {
    Face f;
    f.v[0] = a, f.v[1] = b, f.v[2] = c;
    f.n = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
    const double len = f.n.norm();
    f.n = len > 0 ? Vector3(f.n / len) : Vector3::Zero();
    f.d = f.n.dot(p_[a]);
    const int id = static_cast<int>(faces_.size());
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = edges_.emplace(EdgeKey(f.v[k], f.v[(k + 1) % 3]), id);
      if (!inserted) consistent_ = false, it->second = id;
    }
    faces_.push_back(std::move(f));
    return id;
  }

  void InitialSimplex() {
    // Extreme points along the axes; the farthest pair spans the first edge.
    int ext[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < static_cast<int>(p_.size()); ++i)
      for (int a = 0; a < 3; ++a) {
        if (p_[i][a] < p_[ext[2 * a]][a]) ext[2 * a] = i;
        if (p_[i][a] > p_[ext[2 * a + 1]][a]) ext[2 * a + 1] = i;
      }
    int i0 = 0, i1 = 0;
    double best = -1;
    for (int a = 0; a < 6; ++a)
      for (int b = a + 1; b < 6; ++b) {
        const double d = (p_[ext[a]] - p_[ext[b]]).squaredNorm();
        if (d > best) best = d, i0 = ext[a], i1 = ext[b];
      }
    const Vector3 axis = (p_[i1] - p_[i0]).normalized();
    int i2 = -1;
    best = -1;
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      const Vector3 r = p_[i] - p_[i0];
      const double d = (r - r.dot(axis) * axis).squaredNorm();
      if (d > best) best = d, i2 = i;
    }
    const Vector3 n = (p_[i1] - p_[i0]).cross(p_[i2] - p_[i0]).normalized();
    int i3 = -1;
    best = -1;
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      const double d = std::fabs(n.dot(p_[i] - p_[i0]));
      if (d > best) best = d, i3 = i;
    }
    if (best <= eps_) throw std::invalid_argument("convex hull: points are coplanar");
    // Orient the base so that i3 lies below it (outward normals).
    if (n.dot(p_[i3] - p_[i0]) > 0) std::swap(i1, i2);
    MakeFace(i0, i1, i2);
    MakeFace(i0, i3, i1);
    MakeFace(i1, i3, i2);
    MakeFace(i2, i3, i0);
  }

  // Gives each point to the first face (from `first_face` on) it lies above.
  void Assign(const std::vector<int>& points, size_t first_face) {
    for (int i : points)
      for (size_t f = first_face; f < faces_.size(); ++f)
        if (faces_[f].alive && Dist(faces_[f], i) > eps_) {
          faces_[f].outside.push_back(i);
          break;
        }
  }

  void AddPoint(size_t f0) {
    // Farthest outside point of this face is surely a hull vertex.
    const std::vector<int>& out = faces_[f0].outside;
    int eye = out[0];
    for (int i : out)
      if (Dist(faces_[f0], i) > Dist(faces_[f0], eye)) eye = i;
    // Faces the eye sees, found by flooding across edges from f0.
    std::vector<int> visible = {static_cast<int>(f0)}, horizon;
    faces_[f0].alive = false;
    for (size_t k = 0; k < visible.size(); ++k) {
      const Face& f = faces_[visible[k]];
      for (int e = 0; e < 3; ++e) {
        const int a = f.v[e], b = f.v[(e + 1) % 3];
        auto it = edges_.find(EdgeKey(b, a));
        if (it == edges_.end()) { consistent_ = false; continue; }
        Face& g = faces_[it->second];
        if (!g.alive) continue;
        if (Dist(g, eye) > eps_) {
          g.alive = false;
          visible.push_back(it->second);
        }
      }
    }
    // Horizon: edges of visible faces whose neighbour stayed alive.
    std::vector<std::pair<int, int>> rim;
    std::vector<int> orphans;
    for (int fi : visible) {
      Face& f = faces_[fi];
      for (int e = 0; e < 3; ++e) {
        const int a = f.v[e], b = f.v[(e + 1) % 3];
        auto it = edges_.find(EdgeKey(b, a));
        if (it != edges_.end() && faces_[it->second].alive) rim.emplace_back(a, b);
      }
      for (int i : f.outside)
        if (i != eye) orphans.push_back(i);
      f.outside.clear();
      f.outside.shrink_to_fit();
    }
    for (int fi : visible)
      for (int e = 0; e < 3; ++e) {
        auto it = edges_.find(EdgeKey(faces_[fi].v[e], faces_[fi].v[(e + 1) % 3]));
        if (it != edges_.end() && it->second == fi) edges_.erase(it);
      }
    const size_t first_new = faces_.size();
    for (const auto& [a, b] : rim) MakeFace(a, b, eye);
    Assign(orphans, first_new);
  }

  ConvexHull Collect() const {
    ConvexHull hull;
    std::vector<int> remap(p_.size(), -1);
    for (const Face& f : faces_) {
      if (!f.alive) continue;
      Eigen::Vector3i t;
      for (int k = 0; k < 3; ++k) {
        int& r = remap[f.v[k]];
        if (r < 0) r = static_cast<int>(hull.vertices.size()), hull.vertices.push_back(p_[f.v[k]]);
        t[k] = r;
      }
      hull.triangles.push_back(t);
    }
    hull.consistent = consistent_ && edges_.size() == 3 * hull.triangles.size();
    return hull;
  }

  const std::vector<Vector3>& p_;
  std::vector<Face> faces_;
  std::unordered_map<uint64_t, int> edges_;  // directed edge -> face holding it
  double eps_ = 0.0;
  bool consistent_ = true;
};

}  // namespace

ConvexHull ComputeConvexHull(const std::vector<pd::Vector3>& points) {
  return QuickHull(points).Run();
}

}  // namespace pd_bench
