#pragma once
// Probe triangles placed in the scene frame S for one query: vertices at the
// query's translation offset_S and the face normal, kept in a small
// direct-mapped table. Near a contact a probe triangle meets several scene
// leaves; each would transform it again (a median warm query: 5-8% of its
// time). Lives on the stack of one query (fixed size, no allocation).
#include <array>

#include "pd_core/proximity/model_pair.h"

namespace pd {

class PlacedProbeTriangles {
 public:
  struct Triangle {
    int t = -1;
    Vector3 p[3];  // vertices in S, translated by offset_S (m)
    Vector3 n;     // unit face normal in S
  };

  PlacedProbeTriangles(const ModelPair& pair, const Vector3& offset_S)
      : pair_(pair), offset_S_(offset_S) {}

  // Probe triangle t placed in S.
  const Triangle& operator()(int t) {
    Triangle& slot = table_[t & (kSize - 1)];
    if (slot.t != t) {
      slot.t = t;
      pair_.ProbeTriangle(t, offset_S_, slot.p);
      slot.n = pair_.X_SP.R_SP * pair_.P.face_normals()[t];
    }
    return slot;
  }

 private:
  static constexpr int kSize = 32;  // a power of two
  const ModelPair& pair_;
  const Vector3 offset_S_;
  std::array<Triangle, kSize> table_;
};

}  // namespace pd
