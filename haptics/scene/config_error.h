#pragma once
// A configuration value that cannot be used. what() reads
// "<file>: <key>: <problem and allowed values>", e.g.
// "config/box_on_box.yaml: coupling.translational.stiffness: must be a number
// in (0, 100000] N/m, got -5".
#include <stdexcept>
#include <string>

namespace haptics {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string file, std::string key, const std::string& problem)
      : std::runtime_error(file + ": " + (key.empty() ? "" : key + ": ") + problem),
        file_(std::move(file)), key_(std::move(key)) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }

 private:
  std::string file_;
  std::string key_;
};

}  // namespace haptics
