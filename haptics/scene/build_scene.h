#pragma once
// Turns a SceneConfig into collision geometries (pd::Geometry): primitives
// (plane -> half-space, sphere, box, capsule, cylinder) directly, meshes from
// files (pd::LoadMesh) or generated, their precomputation (pd::CollisionModel)
// built or read from the disk cache (pd_core/mesh/model_cache.h) when a cache
// directory is given. A mesh declared `convex: true` is verified here. Any
// failure throws ConfigError naming the config file and the shape's key (e.g.
// objects[1].shape) with the reason.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "haptics/scene/config_error.h"
#include "haptics/scene/scene_config.h"
#include "haptics/scene/scene_object.h"
#include "pd_core/geometry/geometry.h"
#include "pd_core/mesh/mesh.h"

namespace haptics {

struct SceneModels {
  std::shared_ptr<const pd::Geometry> tool;  // in its geometry frame G
  Isometry3 X_TG = Isometry3::Identity();    // G in the tool frame T
  std::vector<SceneObject> objects;
};

// The triangle mesh of a mesh-type shape (file or procedural) in its own
// frame; ConfigError for a primitive type.
pd::TriangleMesh MakeShapeMesh(const ShapeConfig& shape, const std::string& config_file);

// Mesh geometries already built, by mesh content and convex flag.
using SharedGeometries = std::map<std::string, std::shared_ptr<const pd::Geometry>>;

// The geometry of one shape. cache_dir: see pd_core/mesh/model_cache.h ("" = none).
// With `shared`, a mesh identical to one built before reuses its geometry.
std::shared_ptr<const pd::Geometry> MakeShapeGeometry(const ShapeConfig& shape,
                                                      const std::string& config_file,
                                                      const std::string& cache_dir = "",
                                                      SharedGeometries* shared = nullptr);

// cache_dir overrides config.cache_dir when not empty. Identical meshes in
// the scene share one geometry (immutable, so sharing is safe).
SceneModels BuildSceneModels(const SceneConfig& config, const std::string& cache_dir = "");

}  // namespace haptics
