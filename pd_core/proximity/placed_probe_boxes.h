#pragma once
// Probe BVH node boxes placed in the scene frame S for the box tests of
// box_overlap.h, and what keeps placing them cheap: a memo of the last
// node (a descent splitting the scene side tests one probe node against
// both children), a per-query table of boxes at the probe's rotation (all
// of a PolyDepth query's descents share the rotation and differ in the
// translation only), and for translational CCD the sweep's constants.
#include <array>
#include <cmath>
#include <cstdint>

#include "pd_core/geometry/relative_pose.h"
#include "pd_core/proximity/bvh.h"

namespace pd {

// A probe node box placed in S: axes and centre, with the probe moved by
// an extra translation offset_S.
struct ProbeBoxInS {
  Matrix3 R_SA;
  Vector3 p_SA;
  const Vector3* half_A;
  Vector3 aabb_half_S;  // half extents of the box's axis-aligned bounds in S (m)
  double radius;        // bounding-sphere radius (m)
};

inline ProbeBoxInS ProbeBox(const BvhNode& node, const RelativePose& X_SP,
                            const Vector3& offset_S) {
  const Matrix3 R_SA = X_SP.R_SP * node.R_MB;
  return {R_SA, X_SP * node.center_M + offset_S, &node.half_B, R_SA.cwiseAbs() * node.half_B,
          node.radius};
}

// Probe node boxes at one probe pose without the query's translation, in a
// direct-mapped table by node index. A cold PolyDepth query runs ~10^3
// descents at one rotation; half of their box tests placed a probe box
// (a rotation product each), mostly one placed before (cold queries -5%,
// same answers bit for bit). 1024 entries (140 kB, within L2): 256 and
// 4096 were slower. Owned by a solver; no allocation after construction.
class ProbeBoxCache {
 public:
  // Forgets every box (a new probe pose).
  void Invalidate() { ++generation_; }
  // ProbeBox(node, X_SP, offset_S) for the probe node at `index`, X_SP
  // being the pose of every call since the last Invalidate.
  ProbeBoxInS Get(const BvhNode& node, int32_t index, const RelativePose& X_SP,
                  const Vector3& offset_S) {
    Entry& e = table_[index & (kSize - 1)];
    const uint64_t tag = (generation_ << 32) | static_cast<uint32_t>(index);
    if (e.tag != tag) {
      e.tag = tag;
      e.box = ProbeBox(node, X_SP, Vector3::Zero());
    }
    ProbeBoxInS box = e.box;
    box.p_SA += offset_S;  // (X_SP * c + 0) + offset_S: ProbeBox's sum
    return box;
  }

 private:
  static constexpr int kSize = 1024;  // a power of two
  struct Entry {
    uint64_t tag = 0;  // generation << 32 | node index; 0: never filled
    ProbeBoxInS box;
  };
  uint64_t generation_ = 1;
  std::array<Entry, kSize> table_;
};

// ProbeBox of the node last asked for, kept for the next call, from the
// cache if one is given (with the probe's node array, for the index).
// The probe's pose and translation are fixed for the memo's lifetime.
class ProbeBoxMemo {
 public:
  ProbeBoxMemo(const RelativePose& X_SP, const Vector3& offset_S, ProbeBoxCache* cache = nullptr,
               const BvhNode* nodes = nullptr)
      : X_SP_(X_SP), offset_S_(offset_S), cache_(cache), nodes_(nodes) {}
  const ProbeBoxInS& operator()(const BvhNode& node) {
    if (&node != node_) {
      box_ = Place(node);
      node_ = &node;
    }
    return box_;
  }
  ProbeBoxInS Place(const BvhNode& node) const {
    return cache_ ? cache_->Get(node, static_cast<int32_t>(&node - nodes_), X_SP_, offset_S_)
                  : ProbeBox(node, X_SP_, offset_S_);
  }

 private:
  const RelativePose& X_SP_;
  const Vector3 offset_S_;
  ProbeBoxCache* cache_;
  const BvhNode* nodes_;
  const BvhNode* node_ = nullptr;
  ProbeBoxInS box_;
};

// A translation sweep_S (m per unit of the sweep parameter s) with the
// constants every swept box test of it uses: the reciprocals of its
// components (0 where a component is 0: the tests then skip the division)
// and of its squared length. Computed once per CCD, not per box pair.
struct SweepInS {
  explicit SweepInS(const Vector3& v_S) : v(v_S), qa(v_S.squaredNorm()) {
    for (int i = 0; i < 3; ++i) inv[i] = std::abs(v[i]) < 1e-300 ? 0.0 : 1.0 / v[i];
    inv_qa = qa < 1e-300 ? 0.0 : 1.0 / qa;
  }
  Vector3 v;
  Vector3 inv;
  double qa, inv_qa;
};

// A placed probe box with the sweep along its axes and the reciprocals.
struct SweptProbeBox {
  ProbeBoxInS box;
  Vector3 rate_A;      // R_SA^T sweep_S
  Vector3 inv_rate_A;  // component-wise 1 / rate_A
};

// ProbeBoxMemo for a CCD's swept box tests: the last node's box and its
// sweep along the box axes (three divisions per node, not per pair).
class SweptProbeBoxMemo {
 public:
  SweptProbeBoxMemo(const RelativePose& X_SP, const Vector3& offset_S, const SweepInS& sweep,
                    ProbeBoxCache* cache = nullptr, const BvhNode* nodes = nullptr)
      : place_(X_SP, offset_S, cache, nodes), sweep_(sweep) {}
  const SweptProbeBox& operator()(const BvhNode& node) {
    if (&node != node_) {
      box_.box = place_.Place(node);
      box_.rate_A = box_.box.R_SA.transpose() * sweep_.v;
      box_.inv_rate_A = box_.rate_A.cwiseInverse();
      node_ = &node;
    }
    return box_;
  }

 private:
  ProbeBoxMemo place_;
  const SweepInS& sweep_;
  const BvhNode* node_ = nullptr;
  SweptProbeBox box_;
};

}  // namespace pd
