// libFuzzer target: arbitrary bytes as a scene file (YAML) through the real
// haptics::LoadSceneConfig. The file sits in a private directory next to a
// link to the shipped config/devices, so `device: devices/sigma7.yaml`
// resolves as in config/. Contract: a SceneConfig, or a haptics::ConfigError
// whose message begins with the file it is about. Anything else is a bug.
#include <filesystem>
#include <string>

#include "fuzz_temp_file.h"
#include "haptics/scene/load_scene_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool linked = [] {
    const std::filesystem::path devices = std::filesystem::path(pd_fuzz::TempDir()) / "devices";
    std::error_code ec;
    if (!std::filesystem::exists(devices, ec))
      std::filesystem::create_directory_symlink(PD_FUZZ_CONFIG_DIR "/devices", devices);
    return true;
  }();
  (void)linked;
  const std::string path = pd_fuzz::WriteTempFile("scene.yaml", data, size);
  try {
    const haptics::SceneConfig config = haptics::LoadSceneConfig(path);
    if (config.servo.rate_hz <= 0.0 || config.tool.mass <= 0.0 || config.contact.stiffness <= 0.0)
      pd_fuzz::Violation("accepted a non-positive rate, mass or stiffness");
  } catch (const haptics::ConfigError& e) {
    // The scene file, or the device profile it names.
    if (e.file().empty() || std::string(e.what()).rfind(e.file() + ": ", 0) != 0)
      pd_fuzz::Violation(std::string("ConfigError does not begin with a file name: ") + e.what());
  } catch (const std::exception& e) {
    pd_fuzz::Violation(std::string("unexpected exception type: ") + e.what());
  }
  return 0;
}
