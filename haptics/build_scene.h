#pragma once
// Turns a SceneConfig into collision models: procedural shapes are generated,
// mesh files loaded (pd::LoadMesh), and the tool geometry placed in the tool
// frame by X_TG. Any failure throws ConfigError naming the config file and the
// shape's key (e.g. objects[1].shape) with the reason.
#include <memory>
#include <vector>

#include "haptics/config_error.h"
#include "haptics/scene_config.h"
#include "haptics/scene_object.h"
#include "pd_core/collision_model.h"
#include "pd_core/mesh.h"

namespace haptics {

struct SceneModels {
  std::shared_ptr<const pd::CollisionModel> tool;  // in the tool frame T
  std::vector<SceneObject> objects;
};

// The mesh of one shape in its own frame.
pd::TriangleMesh MakeShapeMesh(const ShapeConfig& shape, const std::string& config_file);

SceneModels BuildSceneModels(const SceneConfig& config);

}  // namespace haptics
