#pragma once
// Writes a small file under GoogleTest's temporary directory for a test.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace probes {

inline std::string WriteTempFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "probes_tests_" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace probes
