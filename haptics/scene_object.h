#pragma once
// A static scene object ready for contact queries.
#include <memory>
#include <string>

#include "haptics/spatial.h"
#include "pd_core/collision_model.h"

namespace haptics {

struct SceneObject {
  std::string name;
  std::shared_ptr<const pd::CollisionModel> model;  // in its mesh frame S
  Isometry3 X_WS = Isometry3::Identity();
};

}  // namespace haptics
