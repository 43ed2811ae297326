#pragma once
// A private scratch directory for a test: made fresh under $TMPDIR (or /tmp)
// by mkdtemp, so parallel test processes never share one, and removed with
// everything in it when the object goes, so a test run leaves nothing behind.
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace pd::test {

class ScopedTempDir {
 public:
  // `tag` names the directory (<tmp>/<tag>_XXXXXX), for whoever finds one
  // left by a crashed test.
  explicit ScopedTempDir(const std::string& tag) {
    std::string pattern = (std::filesystem::temp_directory_path() / (tag + "_XXXXXX")).string();
    if (mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("cannot make a temporary directory " + pattern);
    path_ = pattern;
  }
  ~ScopedTempDir() {
    std::error_code ignored;  // a destructor must not throw; nothing to do if it fails
    std::filesystem::remove_all(path_, ignored);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace pd::test
