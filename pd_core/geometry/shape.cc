#include "pd_core/geometry/shape.h"

namespace pd {

const char* ShapeKindName(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::kHalfSpace: return "half_space";
    case ShapeKind::kSphere: return "sphere";
    case ShapeKind::kBox: return "box";
    case ShapeKind::kCapsule: return "capsule";
    case ShapeKind::kCylinder: return "cylinder";
    case ShapeKind::kConvexMesh: return "convex_mesh";
    case ShapeKind::kMesh: return "mesh";
  }
  return "unknown";
}

}  // namespace pd
