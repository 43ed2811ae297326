// Mesh files declaring millions of triangles are refused by pd::LoadMesh's
// configurable limit (MeshLoadOptions::max_triangles, default 5M) with a
// message naming the file and the limit, before anything of that size is
// allocated. The files are sparse (their size matches their header, the
// body is a hole), so the test needs neither disk nor memory for them.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "pd_core/mesh/load_mesh.h"
#include "tests/scoped_temp_dir.h"

namespace pd {
namespace {

namespace fs = std::filesystem;

// Writes `header` and extends the file to `size` bytes without writing them.
std::string SparseFile(const std::string& name, const std::string& header, uintmax_t size) {
  static const pd::test::ScopedTempDir dir("pd_mesh_limit");  // removed at exit
  const fs::path path = dir / name;
  std::ofstream(path, std::ios::binary) << header;
  fs::resize_file(path, size);
  return path.string();
}

long MaxRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

void ExpectRefused(const std::string& path, const MeshLoadOptions& options, const std::string& count) {
  try {
    LoadMesh(path, options);
    ADD_FAILURE() << path << " was loaded";
  } catch (const MeshLoadError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;
    EXPECT_NE(what.find("max_triangles = " + std::to_string(options.max_triangles)), std::string::npos)
        << what;
    EXPECT_NE(what.find(count), std::string::npos) << what;
  }
}

TEST(MeshSizeLimit, MillionsOfTrianglesAreRefusedBeforeAllocating) {
  const long rss_before = MaxRssKb();
  const uint32_t n = 6'000'000;  // over the 5M default
  // Binary STL: 80-byte header, count, 50 bytes per triangle (300 MB).
  std::string stl(80, ' ');
  for (int i = 0; i < 4; ++i) stl.push_back(static_cast<char>((n >> (8 * i)) & 0xff));
  ExpectRefused(SparseFile("huge.stl", stl, 84 + 50ull * n), MeshLoadOptions{}, "6000000");
  // ASCII OFF and PLY headers with a body long enough to hold the counts.
  ExpectRefused(SparseFile("huge.off", "OFF\n3 6000000 0\n", 13'000'000), MeshLoadOptions{}, "6000000");
  ExpectRefused(SparseFile("huge.ply",
                           "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 6000000\nproperty list uchar int vertex_indices\n"
                           "end_header\n",
                           13'000'000),
                MeshLoadOptions{}, "6000000");
  // The limit is configurable both ways.
  MeshLoadOptions small;
  small.max_triangles = 1'000'000;
  ExpectRefused(SparseFile("two_million.stl", stl.substr(0, 80) + std::string("\x80\x84\x1e\x00", 4),
                           84 + 50ull * 2'000'000),
                small, "2000000");
  // Nothing of that size was allocated (a 6M-triangle mesh needs > 100 MB).
  EXPECT_LT(MaxRssKb() - rss_before, 50'000);
}

}  // namespace
}  // namespace pd
