#pragma once
// Reads one `shape:` map of a scene file into a ShapeConfig. Mesh paths are
// resolved against `config_dir` unless absolute, and must exist. Types and
// their keys are documented in config/box_on_box.yaml; whether a plane may be
// used (not as the tool) is the caller's check (IsPlane).
#include <string>

#include "haptics/scene/scene_config.h"
#include "haptics/scene/yaml_reader.h"

namespace haptics {

// Shape types accepted in `type:`.
const std::vector<std::string>& ShapeTypeNames();

ShapeConfig ReadShapeConfig(const YamlMap& shape, const std::string& config_dir);

// True for the unbounded `plane` shape.
bool IsPlane(const ShapeConfig& shape);

}  // namespace haptics
