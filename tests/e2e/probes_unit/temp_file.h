#pragma once
// Scratch files for the probes tests, in one private directory per test
// process that is removed (with them) at exit.
#include <fstream>
#include <string>

#include "tests/scoped_temp_dir.h"

namespace probes {

// The path of a scratch file called `name` (not created).
inline std::string TempPath(const std::string& name) {
  static const pd::test::ScopedTempDir dir("probes_tests");
  return (dir / name).string();
}

inline std::string WriteTempFile(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace probes
