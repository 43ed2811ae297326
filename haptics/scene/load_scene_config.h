#pragma once
// Reads a scene file (config/*.yaml) and the device profile it names
// (config/devices/*.yaml). Every value is checked at start-up: a bad one
// throws ConfigError naming the file, the full key path and the allowed range;
// unknown keys are warned about (spdlog warn and SceneConfig::warnings); a
// missing mesh file is named. The format, with units, is documented in
// config/box_on_box.yaml.
#include <string>

#include "haptics/scene/config_error.h"
#include "haptics/scene/scene_config.h"

namespace haptics {

// Scene file; `device:` is resolved against the scene file's directory.
SceneConfig LoadSceneConfig(const std::string& path);

// Device profile on its own. Warnings go to *warnings if given.
DeviceConfig LoadDeviceConfig(const std::string& path, std::vector<std::string>* warnings = nullptr);

}  // namespace haptics
