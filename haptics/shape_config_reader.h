#pragma once
// Reads one `shape:` map of a scene file into a ShapeConfig. Mesh paths are
// resolved against `config_dir` unless absolute, and must exist.
#include <string>

#include "haptics/scene_config.h"
#include "haptics/yaml_reader.h"

namespace haptics {

// Shape types accepted in `type:`.
const std::vector<std::string>& ShapeTypeNames();

ShapeConfig ReadShapeConfig(const YamlMap& shape, const std::string& config_dir);

}  // namespace haptics
