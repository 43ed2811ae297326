#pragma once
// Tests that need a file an install step provides (Debian's mesh packages,
// scripts/fetch_meshes.sh). On a developer machine without it the test is
// skipped with the step to take; under CI (CI=true) a missing prerequisite
// fails the test instead, because a skip there would hide a missing install
// step.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cctype>
#include <filesystem>
#include <string>

namespace pd::test {

// CI set to anything but "", "0" or "false" (any case).
inline bool InCi() {
  const char* ci = std::getenv("CI");
  if (ci == nullptr) return false;
  std::string v(ci);
  for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return !(v.empty() || v == "0" || v == "false");
}

}  // namespace pd::test

// In a test body: fails (CI) or skips (elsewhere) the test when `path` does
// not exist; `how` says how to provide it.
#define PD_REQUIRE_FILE(path, how)                                                      \
  do {                                                                                  \
    const std::string pd_required_path_ = (path);                                       \
    if (!std::filesystem::exists(pd_required_path_)) {                                  \
      if (::pd::test::InCi())                                                            \
        GTEST_FAIL() << pd_required_path_ << " missing under CI (" << (how)             \
                     << "): a missing prerequisite fails in CI";                        \
      GTEST_SKIP() << pd_required_path_ << " missing (" << (how) << ")";                \
    }                                                                                   \
  } while (0)
