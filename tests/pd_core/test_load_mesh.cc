#include "pd_core/mesh/load_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pd_core/geometry/make_shapes.h"
#include "tests/prerequisites.h"
#include "tests/scoped_temp_dir.h"

namespace pd {
namespace {

namespace fs = std::filesystem;

const std::string kMeshDir = PD_TEST_MESH_DIR;
const std::string kAssimpModels = PD_ASSIMP_MODELS_DIR;

// Per-test scratch directory (tests may run as parallel processes).
class LoadMeshTest : public ::testing::Test {
 protected:
  std::string Write(const std::string& name, const std::string& contents) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << contents;
    return path;
  }

  pd::test::ScopedTempDir tmp_{"pd_load_mesh"};
  const fs::path dir_ = tmp_.path();
};

std::string Off(const std::vector<Vector3>& v, const std::vector<std::vector<int>>& faces) {
  std::ostringstream s;
  s.precision(17);
  s << "OFF\n" << v.size() << " " << faces.size() << " 0\n";
  for (const Vector3& p : v) s << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& f : faces) {
    s << f.size();
    for (int i : f) s << " " << i;
    s << "\n";
  }
  return s.str();
}

std::string Off(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> faces;
  for (const auto& t : mesh.triangles) faces.push_back({t[0], t[1], t[2]});
  return Off(mesh.vertices, faces);
}

// Every triangle as its own facet, as STL stores it (normals deliberately
// wrong: the loader must ignore them when welding).
std::string BinaryStl(const TriangleMesh& mesh) {
  std::string out(80, ' ');
  auto put_u32 = [&](uint32_t x) { out.append(reinterpret_cast<const char*>(&x), 4); };
  auto put_f32 = [&](double x) {
    const float f = static_cast<float>(x);
    out.append(reinterpret_cast<const char*>(&f), 4);
  };
  put_u32(mesh.num_triangles());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) put_f32(k == 0 ? 1.0 : 0.0);
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) put_f32(mesh.vertices[t[k]][d]);
    out.append(2, '\0');
  }
  return out;
}

std::string AsciiStl(const TriangleMesh& mesh) {
  std::ostringstream s;
  s.precision(9);
  s << "solid test\n";
  for (const auto& t : mesh.triangles) {
    s << " facet normal 0 0 1\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Vector3& p = mesh.vertices[t[k]];
      s << "   vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
    s << "  endloop\n endfacet\n";
  }
  s << "endsolid test\n";
  return s.str();
}

// An OFF file read independently of assimp: vertices and triangle faces.
struct OffFile {
  std::vector<Vector3> vertices;
  std::vector<std::array<int, 3>> triangles;
};
OffFile ReadTriangleOff(const std::string& path) {
  std::ifstream in(path);
  std::string keyword;
  size_t nv = 0, nf = 0, ne = 0;
  in >> keyword >> nv >> nf >> ne;
  OffFile off;
  off.vertices.resize(nv);
  for (Vector3& v : off.vertices) in >> v.x() >> v.y() >> v.z();
  for (size_t f = 0; f < nf; ++f) {
    int n = 0;
    std::array<int, 3> t{};
    in >> n >> t[0] >> t[1] >> t[2];
    EXPECT_EQ(n, 3) << path << " face " << f;
    off.triangles.push_back(t);
  }
  EXPECT_TRUE(in.good()) << path;
  return off;
}

bool StartsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// LoadMesh must refuse `path` with a message "<path>: ..." mentioning `problem`.
::testing::AssertionResult Refused(const std::string& path, const MeshLoadOptions& options,
                                   const std::string& problem) {
  try {
    LoadMesh(path, options);
  } catch (const MeshLoadError& e) {
    const std::string message = e.what();
    if (!StartsWith(message, path + ": "))
      return ::testing::AssertionFailure() << "message does not begin with the path: " << message;
    if (message.find(problem) == std::string::npos)
      return ::testing::AssertionFailure() << "message does not mention '" << problem << "': " << message;
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << path << " loaded but should have been refused";
}
::testing::AssertionResult Refused(const std::string& path, const std::string& problem) {
  return Refused(path, MeshLoadOptions{}, problem);
}

bool HasWarning(const LoadedMesh& loaded, const std::string& a, const std::string& b) {
  for (const std::string& w : loaded.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

// ---------------------------------------------------------------- real files

TEST_F(LoadMeshTest, KnotOffIsClosedAndKeepsFileCoordinatesTimesScale) {
  const std::string path = kMeshDir + "/knot1.off";
  PD_REQUIRE_FILE(path, "run scripts/fetch_meshes.sh");
  const OffFile file = ReadTriangleOff(path);
  MeshLoadOptions options;
  options.scale = 0.01;
  const LoadedMesh loaded = LoadMesh(path, options);
  EXPECT_EQ(loaded.mesh.name, path);
  EXPECT_EQ(loaded.mesh.num_triangles(), 6400);
  EXPECT_EQ(loaded.mesh.num_vertices(), 3200);
  EXPECT_TRUE(loaded.topology.closed()) << loaded.topology.Describe();
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  // Same triangles in the same order, corners at file coordinates (read as
  // 32-bit floats by assimp) times the scale.
  ASSERT_EQ(file.triangles.size(), 6400u);
  for (size_t t = 0; t < file.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vector3 expected = 0.01 * file.vertices[file.triangles[t][k]];
      const Vector3& got = loaded.mesh.vertices[loaded.mesh.triangles[t][k]];
      ASSERT_LT((got - expected).norm(), 1e-6 * (1.0 + expected.norm())) << "triangle " << t;
    }
  }
}

TEST_F(LoadMeshTest, CowOffIsClosed) {
  const std::string path = kMeshDir + "/cow.off";
  PD_REQUIRE_FILE(path, "run scripts/fetch_meshes.sh");
  const LoadedMesh loaded = LoadMesh(path);
  EXPECT_EQ(loaded.mesh.num_triangles(), 5804);
  EXPECT_TRUE(loaded.topology.closed()) << loaded.topology.Describe();
  EXPECT_EQ(loaded.topology.num_degenerate_triangles, 0);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST_F(LoadMeshTest, MushroomOffIsOpenAndWarnsByName) {
  const std::string path = kMeshDir + "/mushroom.off";
  PD_REQUIRE_FILE(path, "run scripts/fetch_meshes.sh");
  const LoadedMesh loaded = LoadMesh(path);
  EXPECT_EQ(loaded.mesh.num_triangles(), 4608);
  EXPECT_FALSE(loaded.topology.closed());
  EXPECT_GT(loaded.topology.num_boundary_edges, 0);
  EXPECT_TRUE(HasWarning(loaded, path, "open")) << ::testing::PrintToString(loaded.warnings);
}

TEST_F(LoadMeshTest, AssimpModelsInEveryFormat) {
  struct Case {
    std::string file;
    int triangles, vertices;
    bool closed;
  };
  const std::vector<Case> cases = {
      {"OBJ/box.obj", 12, 8, true},          // quads triangulated
      {"OBJ/cube_usemtl.obj", 12, 8, true},  // three sub-meshes welded together
      {"OFF/Cube.off", 12, 8, true},
      {"PLY/cube.ply", 12, 8, true},
      {"PLY/cube_binary.ply", 12, 8, true},
      {"PLY/cube_uv.ply", 12, 8, true},  // texture seams do not split vertices
      {"STL/sphereWithHole.stl", 285, 146, false},
  };
  for (const Case& c : cases) {
    const std::string path = kAssimpModels + "/" + c.file;
    PD_REQUIRE_FILE(path, "apt-get install assimp-testmodels");
    const LoadedMesh loaded = LoadMesh(path);
    EXPECT_EQ(loaded.mesh.num_triangles(), c.triangles) << c.file;
    EXPECT_EQ(loaded.mesh.num_vertices(), c.vertices) << c.file;
    EXPECT_EQ(loaded.topology.closed(), c.closed) << c.file << ": " << loaded.topology.Describe();
    EXPECT_EQ(HasWarning(loaded, path, "open"), !c.closed) << c.file;
  }
}

TEST_F(LoadMeshTest, SpiderStlBinaryAndAsciiAgree) {
  const std::string binary = kAssimpModels + "/STL/Spider_binary.stl";
  const std::string ascii = kAssimpModels + "/STL/Spider_ascii.stl";
  PD_REQUIRE_FILE(binary, "apt-get install assimp-testmodels");
  PD_REQUIRE_FILE(ascii, "apt-get install assimp-testmodels");
  const LoadedMesh a = LoadMesh(binary), b = LoadMesh(ascii);
  ASSERT_EQ(a.mesh.num_triangles(), b.mesh.num_triangles());
  ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices());
  EXPECT_LT(a.mesh.num_vertices(), a.mesh.num_triangles());  // facets were welded
  for (int t = 0; t < a.mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vector3& pa = a.mesh.vertices[a.mesh.triangles[t][k]];
      const Vector3& pb = b.mesh.vertices[b.mesh.triangles[t][k]];
      ASSERT_LT((pa - pb).norm(), 1e-5 * (1.0 + pa.norm()));
    }
  }
}

TEST_F(LoadMeshTest, WusonIsTheSameMeshInEveryFormat) {
  int vertices = -1;
  for (const char* file : {"OFF/Wuson.off", "STL/Wuson.stl", "PLY/Wuson.ply", "OBJ/WusonOBJ.obj"}) {
    const std::string path = kAssimpModels + "/" + file;
    PD_REQUIRE_FILE(path, "apt-get install assimp-testmodels");
    const LoadedMesh loaded = LoadMesh(path);
    EXPECT_EQ(loaded.mesh.num_triangles(), 3732) << file;
    // The PLY carries texture coordinates; positions alone decide welding.
    if (vertices < 0) vertices = loaded.mesh.num_vertices();
    EXPECT_EQ(loaded.mesh.num_vertices(), vertices) << file;
  }
}

// ------------------------------------------------------ generated good files

TEST_F(LoadMeshTest, StlFacetsWeldIntoAClosedManifold) {
  const TriangleMesh sphere = MakeIcosphere(0.05, 2);
  for (const auto& [name, contents] : {std::pair{"ball_binary.stl", BinaryStl(sphere)},
                                       std::pair{"ball_ascii.stl", AsciiStl(sphere)}}) {
    const LoadedMesh loaded = LoadMesh(Write(name, contents));
    EXPECT_EQ(loaded.mesh.num_triangles(), sphere.num_triangles()) << name;
    EXPECT_EQ(loaded.mesh.num_vertices(), sphere.num_vertices()) << name;
    EXPECT_TRUE(loaded.topology.closed()) << name << ": " << loaded.topology.Describe();
    EXPECT_TRUE(loaded.warnings.empty()) << name << ": " << loaded.warnings.front();
  }
}

TEST_F(LoadMeshTest, ScaleMultipliesCoordinatesWithoutRecentring) {
  TriangleMesh box = MakeBox(Vector3(0.5, 1.0, 2.0));
  for (Vector3& v : box.vertices) v += Vector3(10.0, 20.0, 30.0);
  const std::string path = Write("box.off", Off(box));
  const LoadedMesh unit = LoadMesh(path);
  MeshLoadOptions options;
  options.scale = 0.25;
  const LoadedMesh scaled = LoadMesh(path, options);
  ASSERT_EQ(unit.mesh.num_vertices(), 8);
  ASSERT_EQ(scaled.mesh.num_vertices(), 8);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(unit.mesh.vertices[i], box.vertices[i]);  // exact in float and double
    EXPECT_EQ(scaled.mesh.vertices[i], 0.25 * box.vertices[i]);
  }
  EXPECT_EQ(unit.mesh.triangles, box.triangles);
  EXPECT_TRUE(unit.topology.closed());
}

TEST_F(LoadMeshTest, DegenerateTrianglesAreDroppedWithAWarning) {
  // A tetrahedron, one face repeating an index and one whose corners 0 and 4
  // coincide in space (welded, so it repeats a vertex too).
  const std::vector<Vector3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
  const std::string path =
      Write("tet.off", Off(v, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 0, 1}, {4, 0, 2}}));
  const LoadedMesh loaded = LoadMesh(path);
  EXPECT_EQ(loaded.mesh.num_triangles(), 4);
  EXPECT_EQ(loaded.mesh.num_vertices(), 4);
  EXPECT_TRUE(loaded.topology.closed());
  EXPECT_TRUE(HasWarning(loaded, path, "dropped 2 degenerate"))
      << ::testing::PrintToString(loaded.warnings);
}

TEST_F(LoadMeshTest, OpenAndInwardMeshesWarn) {
  const std::vector<Vector3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::string open = Write("open.off", Off(v, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}}));
  const LoadedMesh a = LoadMesh(open);
  EXPECT_FALSE(a.topology.closed());
  EXPECT_TRUE(HasWarning(a, open, "open")) << ::testing::PrintToString(a.warnings);
  const std::string inward =
      Write("inward.off", Off(v, {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}));
  const LoadedMesh b = LoadMesh(inward);
  EXPECT_TRUE(b.topology.closed());
  EXPECT_TRUE(HasWarning(b, inward, "inward")) << ::testing::PrintToString(b.warnings);
  const std::string good = Write("good.off", Off(v, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
  EXPECT_TRUE(LoadMesh(good).warnings.empty());
}

// -------------------------------------------------------------- bad input

TEST_F(LoadMeshTest, MissingFileOrDirectory) {
  const std::string missing = (dir_ / "no_such_mesh.obj").string();
  EXPECT_TRUE(Refused(missing, "not found"));
  EXPECT_TRUE(Refused(dir_.string(), "directory"));
}

TEST_F(LoadMeshTest, EmptyFile) {
  EXPECT_TRUE(Refused(Write("empty.off", ""), "empty"));
  EXPECT_TRUE(Refused(Write("empty.stl", ""), "empty"));
}

TEST_F(LoadMeshTest, TruncatedOff) {
  const std::string full = Off(MakeBox(Vector3(1, 1, 1)));  // 2 + 8 + 12 lines
  auto first_lines = [&](int n) {
    size_t end = 0;
    for (int i = 0; i < n; ++i) end = full.find('\n', end) + 1;
    return full.substr(0, end);
  };
  // Short face or vertex list: assimp 5.2.5 only logs these and leaves empty
  // faces, which abort() its triangulation if passed on.
  EXPECT_TRUE(Refused(Write("faces_cut.off", first_lines(20)), "header"));
  EXPECT_TRUE(Refused(Write("vertices_cut.off", first_lines(5)), "header"));
  // Cut inside the last vertex.
  EXPECT_TRUE(Refused(Write("vertex_cut.off", first_lines(9) + "1 1"), "assimp"));
}

TEST_F(LoadMeshTest, OffIndexOutOfRange) {
  // assimp clamps the index silently (only a log line): refused here.
  const std::vector<Vector3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::string path = Write("bad_index.off", Off(v, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 7}}));
  EXPECT_TRUE(Refused(path, "out of range"));
}

TEST_F(LoadMeshTest, GarbageWithStlExtension) {
  std::string garbage;
  for (int i = 0; i < 3000; ++i) garbage.push_back(static_cast<char>((i * 7919) % 251));
  EXPECT_TRUE(Refused(Write("garbage.stl", garbage), "assimp cannot read it"));
}

TEST_F(LoadMeshTest, HeadersDeclaringMoreThanTheFileHolds) {
  // Like assimp's own invalid/OutOfMemory.off, which gets a process killed if
  // passed to assimp: refused from the header alone.
  const std::string off = Write("huge.off", "OFF\n353535235358 6 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(Refused(off, "header declares 353535235358 vertices"));
  const std::string ply = Write("huge.ply",
                                "ply\nformat ascii 1.0\nelement vertex 4000000000\n"
                                "property float x\nproperty float y\nproperty float z\n"
                                "element face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(Refused(ply, "header declares 4000000000 vertices"));
}

TEST_F(LoadMeshTest, NonFiniteCoordinates) {
  const std::string tet_faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  EXPECT_TRUE(Refused(Write("nan.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 nan\n0 0 1\n" + tet_faces),
                 MeshLoadOptions{}, "non-finite"));
  EXPECT_TRUE(Refused(Write("inf.off", "OFF\n4 4 0\n0 0 0\ninf 0 0\n0 1 0\n0 0 1\n" + tet_faces),
                 MeshLoadOptions{}, "non-finite"));
  // Beyond float range: assimp's 32-bit read turns it into inf.
  EXPECT_TRUE(Refused(Write("big.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1e39 0\n0 0 1\n" + tet_faces),
                 MeshLoadOptions{}, "non-finite"));
  EXPECT_TRUE(Refused(Write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n"),
                 "non-finite"));
}

TEST_F(LoadMeshTest, CoordinatesBeyondTheLimitAfterScaling) {
  const std::string tet_faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string far = Write("far.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 -2e6\n" + tet_faces);
  EXPECT_TRUE(Refused(far, "max_abs_coordinate"));
  const std::string near = Write("near.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 -2\n" + tet_faces);
  EXPECT_NO_THROW(LoadMesh(near));
  MeshLoadOptions big_scale;
  big_scale.scale = 1e6;
  EXPECT_TRUE(Refused(near, big_scale, "max_abs_coordinate"));
  MeshLoadOptions tight;
  tight.max_abs_coordinate = 1.5;
  EXPECT_TRUE(Refused(near, tight, "max_abs_coordinate"));
}

TEST_F(LoadMeshTest, MoreTrianglesThanAllowed) {
  const TriangleMesh sphere = MakeIcosphere(1.0, 1);  // 80 triangles
  MeshLoadOptions options;
  options.max_triangles = 79;
  EXPECT_TRUE(Refused(Write("ball.off", Off(sphere)), options, "max_triangles"));
  EXPECT_TRUE(Refused(Write("ball.stl", BinaryStl(sphere)), options, "max_triangles"));
  EXPECT_TRUE(Refused(Write("ball_ascii.stl", AsciiStl(sphere)), options, "max_triangles"));
  options.max_triangles = 80;
  EXPECT_EQ(LoadMesh(Write("ok.off", Off(sphere)), options).mesh.num_triangles(), 80);
}

TEST_F(LoadMeshTest, NoTriangles) {
  EXPECT_TRUE(Refused(Write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\np 2\np 3\n"),
                 MeshLoadOptions{}, "no triangles"));
  EXPECT_TRUE(Refused(Write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n"),
                 MeshLoadOptions{}, "no triangles"));
  const std::vector<Vector3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_TRUE(Refused(Write("only_degenerate.off", Off(v, {{0, 0, 1}, {1, 2, 2}})),
                 "no triangles"));
}

TEST_F(LoadMeshTest, InvalidScale) {
  const std::string path = Write("box.off", Off(MakeBox(Vector3(1, 1, 1))));
  for (double scale : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    MeshLoadOptions options;
    options.scale = scale;
    EXPECT_TRUE(Refused(path, options, "scale"));
  }
}

}  // namespace
}  // namespace pd
