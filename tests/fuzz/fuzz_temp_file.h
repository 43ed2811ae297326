#pragma once
// For the fuzz targets: writes fuzz bytes to a file in a private temporary
// directory (one per process, made once), so that the loaders under test run
// their real file paths.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "tests/scoped_temp_dir.h"

namespace pd_fuzz {

// The process's private directory (under $TMPDIR or /tmp), removed at exit.
inline const std::string& TempDir() {
  static const pd::test::ScopedTempDir dir("pd_fuzz");
  static const std::string path = dir.path().string();
  return path;
}

// Writes `size` bytes to TempDir()/name and returns the path.
inline std::string WriteTempFile(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = TempDir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("cannot write " + path);
  return path;
}

// A broken contract found by a fuzz target: print it and abort, so that
// libFuzzer keeps the input and the regression replay fails.
[[noreturn]] inline void Violation(const std::string& what) {
  std::fprintf(stderr, "fuzz contract violation: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace pd_fuzz
