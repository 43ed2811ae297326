#pragma once
// A static scene object ready for contact queries: its geometry (primitive,
// convex mesh or general mesh) in its own frame S, placed in world by X_WS.
#include <memory>
#include <string>

#include "haptics/tool/spatial.h"
#include "pd_core/geometry/geometry.h"

namespace haptics {

struct SceneObject {
  std::string name;
  std::shared_ptr<const pd::Geometry> geometry;  // in its frame S
  Isometry3 X_WS = Isometry3::Identity();
};

}  // namespace haptics
