#pragma once
// For the fuzz targets: writes fuzz bytes to a file in a private temporary
// directory (one per process, made once), so that the loaders under test run
// their real file paths.
#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace pd_fuzz {

// The process's private directory (mkdtemp under $TMPDIR or /tmp).
inline const std::string& TempDir() {
  static const std::string dir = [] {
    const char* base = getenv("TMPDIR");
    std::string pattern = std::string(base != nullptr ? base : "/tmp") + "/pd_fuzz_XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed: " + pattern);
    return pattern;
  }();
  return dir;
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
