#pragma once
// Broad phase for one moving tool against many static scene objects: which
// objects can touch the tool's motion over a tick. Objects it skips cost
// nothing.
//
// Bounded objects: their world-frame axis-aligned boxes, computed once at
// construction from the geometry's support function (exact for primitives,
// the convex hull for meshes), in a static binary AABB tree (median split,
// one object per leaf, nodes depth-first). Half-spaces (planes): a candidate
// unless the query box lies wholly above the plane (tested with the box's
// support point along -n). The query box is the tool's swept box: its world
// box at the previous and at the current pose, joined and grown by the
// contact's cull_margin (penalty_wrench.h). Query() does not allocate.
#include <cstdint>
#include <vector>

#include "haptics/scene/scene_object.h"
#include "haptics/tool/spatial.h"
#include "pd_core/geometry/geometry.h"

namespace haptics {

// An axis-aligned box in W (m).
struct WorldBox {
  Vector3 min_W = Vector3::Constant(1.0);
  Vector3 max_W = Vector3::Constant(-1.0);  // default: empty
  bool Overlaps(const WorldBox& o) const {
    return (min_W.array() <= o.max_W.array()).all() && (o.min_W.array() <= max_W.array()).all();
  }
  WorldBox Joined(const WorldBox& o) const { return {min_W.cwiseMin(o.min_W), max_W.cwiseMax(o.max_W)}; }
  WorldBox Grown(double margin) const {
    return {min_W.array() - margin, max_W.array() + margin};
  }
  Vector3 center() const { return 0.5 * (min_W + max_W); }
};

// A box containing bounded geometry g at X_WG, cheap enough for every tick:
// g's own-frame box rotated into W, intersected with its bounding sphere's box
// (both contain g).
WorldBox BoundingBoxInWorld(const pd::Geometry& g, const Isometry3& X_WG);

// The smallest world box of bounded g at X_WG, from its support function
// (load time: for meshes this walks the hull vertices).
WorldBox TightBoundingBoxInWorld(const pd::Geometry& g, const Isometry3& X_WG);

class BroadPhase {
 public:
  explicit BroadPhase(const std::vector<SceneObject>& objects);

  // Indices of the objects whose box overlaps `query_W` and of the planes it
  // reaches, into *candidates (cleared first; reserve num_objects() entries
  // once so that this never allocates). Order: planes, then tree order.
  void Query(const WorldBox& query_W, std::vector<int>* candidates) const;

  int num_objects() const { return num_objects_; }
  int num_planes() const { return static_cast<int>(planes_.size()); }
  // World box of bounded object i (empty box for a plane).
  const WorldBox& object_box(int i) const { return object_boxes_[i]; }

 private:
  struct Node {
    WorldBox box;
    int32_t right = -1;   // internal: right child (left child is the next node)
    int32_t object = -1;  // leaf: the object's index
  };
  struct Plane {
    Vector3 n_W;    // outward unit normal
    double offset;  // the solid is n_W·x <= offset (m)
    int object;
  };
  int Build(std::vector<int>& items, int begin, int end);

  int num_objects_ = 0;
  std::vector<WorldBox> object_boxes_;
  std::vector<Node> nodes_;
  std::vector<Plane> planes_;
};

}  // namespace haptics
