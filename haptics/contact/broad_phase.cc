#include "haptics/contact/broad_phase.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace haptics {
namespace {

// Deeper trees than this cannot come from a median split of < 2^40 objects.
constexpr int kMaxTreeDepth = 64;

}  // namespace

WorldBox BoundingBoxInWorld(const pd::Geometry& g, const Isometry3& X_WG) {
  const Vector3 c_G = 0.5 * (g.aabb_min() + g.aabb_max());
  const Vector3 h_G = 0.5 * (g.aabb_max() - g.aabb_min());
  const Vector3 c_W = X_WG * c_G;
  const Vector3 h_W = X_WG.linear().cwiseAbs() * h_G;
  const Vector3 s_W = X_WG * g.center();
  const Vector3 r = Vector3::Constant(g.radius());
  return {(c_W - h_W).cwiseMax(s_W - r), (c_W + h_W).cwiseMin(s_W + r)};
}

WorldBox TightBoundingBoxInWorld(const pd::Geometry& g, const Isometry3& X_WG) {
  WorldBox box;
  const Matrix3 R_GW = X_WG.linear().transpose();
  for (int i = 0; i < 3; ++i) {
    const Vector3 u_G = R_GW.col(i);  // world axis i in G
    box.max_W[i] = (X_WG * g.Support(u_G))[i];
    box.min_W[i] = (X_WG * g.Support(-u_G))[i];
  }
  return box;
}

BroadPhase::BroadPhase(const std::vector<SceneObject>& objects)
    : num_objects_(static_cast<int>(objects.size())), object_boxes_(objects.size()) {
  std::vector<int> bounded;
  for (int i = 0; i < num_objects_; ++i) {
    const SceneObject& o = objects[i];
    if (!o.geometry) throw std::invalid_argument("BroadPhase: object '" + o.name + "' has no geometry");
    if (o.geometry->bounded()) {
      object_boxes_[i] = TightBoundingBoxInWorld(*o.geometry, o.X_WS);
      bounded.push_back(i);
    } else {
      const Vector3 n_W = o.X_WS.linear().col(2);
      planes_.push_back({n_W, n_W.dot(o.X_WS.translation()), i});
    }
  }
  nodes_.reserve(2 * bounded.size());
  if (!bounded.empty()) Build(bounded, 0, static_cast<int>(bounded.size()));
}

int BroadPhase::Build(std::vector<int>& items, int begin, int end) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  WorldBox box = object_boxes_[items[begin]];
  for (int k = begin + 1; k < end; ++k) box = box.Joined(object_boxes_[items[k]]);
  nodes_[index].box = box;
  if (end - begin == 1) {
    nodes_[index].object = items[begin];
    return index;
  }
  int axis = 0;
  (box.max_W - box.min_W).maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end, [&](int a, int b) {
    return object_boxes_[a].center()[axis] < object_boxes_[b].center()[axis];
  });
  Build(items, begin, mid);
  nodes_[index].right = Build(items, mid, end);
  return index;
}

void BroadPhase::Query(const WorldBox& query_W, std::vector<int>* candidates) const {
  candidates->clear();
  const Vector3 c = query_W.center();
  const Vector3 h = 0.5 * (query_W.max_W - query_W.min_W);
  for (const Plane& p : planes_) {
    // Lowest point of the box along n (its support along -n) at or below the plane.
    if (p.n_W.dot(c) - p.n_W.cwiseAbs().dot(h) <= p.offset) candidates->push_back(p.object);
  }
  if (nodes_.empty()) return;
  std::array<int, kMaxTreeDepth> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.Overlaps(query_W)) continue;
    if (node.object >= 0) {
      candidates->push_back(node.object);
      continue;
    }
    const int left = static_cast<int>(&node - nodes_.data()) + 1;
    stack[top++] = node.right;
    stack[top++] = left;
  }
}

}  // namespace haptics
