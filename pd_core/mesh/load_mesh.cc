#include "pd_core/mesh/load_mesh.h"

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <unordered_map>

namespace pd {
namespace {

namespace fs = std::filesystem;

// TriangleMesh indexes with int: every corner of every triangle must fit.
constexpr int64_t kMaxIndexableTriangles = INT_MAX / 3;

[[noreturn]] void Fail(const std::string& path, const std::string& problem) {
  throw MeshLoadError(path + ": " + problem);
}

std::string Str(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

void CheckOptions(const std::string& path, const MeshLoadOptions& options) {
  if (!std::isfinite(options.scale) || options.scale <= 0.0)
    Fail(path, "scale " + Str(options.scale) + " is invalid (must be finite and > 0)");
  if (options.max_triangles < 1)
    Fail(path, "max_triangles " + std::to_string(options.max_triangles) + " is invalid (must be >= 1)");
  if (!(options.max_abs_coordinate > 0.0))
    Fail(path, "max_abs_coordinate " + Str(options.max_abs_coordinate) + " is invalid (must be > 0)");
}

// assimp reports some damage only in its log: the OFF reader clamps
// out-of-range vertex indices, drops faces of more than 9 vertices and leaves
// faces empty when the file is shorter than its header says. Its process-wide
// logger forwards to a per-thread list while this thread imports a file.
thread_local std::vector<std::string>* t_assimp_messages = nullptr;

class CaptureStream : public Assimp::LogStream {
 public:
  void write(const char* message) override {
    if (t_assimp_messages == nullptr) return;
    std::string m(message);
    while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
    const size_t tag = m.find(": ");  // drop the "Error, T0: " prefix
    t_assimp_messages->push_back(tag == std::string::npos ? m : m.substr(tag + 2));
  }
};

// Collects assimp's errors and warnings emitted on this thread while alive.
class AssimpMessages {
 public:
  AssimpMessages() {
    static std::once_flag once;
    std::call_once(once, [] {
      if (Assimp::DefaultLogger::isNullLogger())
        Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);  // no log file
      Assimp::DefaultLogger::get()->attachStream(new CaptureStream,
                                                 Assimp::Logger::Err | Assimp::Logger::Warn);
    });
    t_assimp_messages = &messages_;
  }
  ~AssimpMessages() { t_assimp_messages = nullptr; }
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  std::vector<std::string> messages_;
};

// Returns the file size; refuses what assimp would report less clearly.
uintmax_t CheckReadable(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) Fail(path, "file not found");
  if (fs::is_directory(status)) Fail(path, "is a directory, not a mesh file");
  if (!std::ifstream(path, std::ios::binary)) Fail(path, "file cannot be opened for reading");
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) Fail(path, "cannot read file size: " + ec.message());
  if (size == 0) Fail(path, "file is empty");
  return size;
}

std::string ReadPrefix(const std::string& path, size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string buf(max_bytes, '\0');
  in.read(buf.data(), static_cast<std::streamsize>(max_bytes));
  buf.resize(static_cast<size_t>(in.gcount()));
  return buf;
}

// Header counts, saturated at 1e18 so sums cannot overflow.
constexpr uint64_t kCountCap = 1'000'000'000'000'000'000ull;

bool ParseCount(const std::string& token, uint64_t* count) {
  if (token.empty() ||
      !std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  *count = token.size() > 18 ? kCountCap : std::min<uint64_t>(std::stoull(token), kCountCap);
  return true;
}

// OFF and PLY readers allocate from the counts in the header before reading
// the body, so a corrupt header can exhaust memory (assimp's own
// invalid/OutOfMemory.off gets the process OOM-killed). Counts must fit the
// file: every vertex or face takes at least `min_bytes` bytes.
void CheckCountsFitFile(const std::string& path, const char* format, uint64_t vertices,
                        uint64_t faces, uint64_t body_bytes, uint64_t min_bytes,
                        int64_t max_triangles) {
  if (vertices + faces > body_bytes / min_bytes)
    Fail(path, std::string(format) + " header declares " + std::to_string(vertices) +
                   " vertices and " + std::to_string(faces) + " faces, more than " +
                   std::to_string(body_bytes) + " bytes can hold (corrupt or truncated file)");
  if (faces > static_cast<uint64_t>(max_triangles))
    Fail(path, std::string(format) + " header declares " + std::to_string(faces) +
                   " faces, more than max_triangles = " + std::to_string(max_triangles));
}

// OFF: optional "#" comments, keyword [ST][C][N][4][n]OFF, [dimension], counts.
void CheckOffHeader(const std::string& path, const std::string& head, uintmax_t size,
                    int64_t max_triangles) {
  std::istringstream in(head);
  std::vector<std::string> tokens;
  std::string line;
  while (tokens.size() < 4 && std::getline(in, line)) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string w;
    while (words >> w) tokens.push_back(w);
  }
  if (tokens.empty()) return;
  const std::string& key = tokens[0];
  if (key.size() < 3 || key.compare(key.size() - 3, 3, "OFF") != 0) return;
  if (key.find_first_not_of("STCN4n", 0) != key.size() - 3) return;
  const size_t first = key.find('n') != std::string::npos ? 2 : 1;  // skip dimension
  uint64_t vertices = 0, faces = 0;
  if (tokens.size() < first + 2 || !ParseCount(tokens[first], &vertices) ||
      !ParseCount(tokens[first + 1], &faces))
    return;  // leave malformed headers to assimp's own message
  CheckCountsFitFile(path, "OFF", vertices, faces, size, 2, max_triangles);  // "0\n"
}

// assimp 5.2's PLY reader loops forever when no header line is exactly
// "end_header" (e.g. "end_headergg", found by fuzzing and kept in
// tests/fuzz/regressions/load_mesh/): require one before assimp reads the
// file. Other unknown header lines are left to assimp, which skips them.
void CheckPlyHeaderEnd(const std::string& path, const std::string& head) {
  std::istringstream in(head);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, 10, "end_header") != 0) continue;
    std::istringstream words(line);
    std::string first, rest;
    words >> first >> rest;
    if (first == "end_header" && rest.empty()) return;
    Fail(path, "PLY header line '" + line.substr(0, 80) + "' is not 'end_header'");
  }
  Fail(path, "PLY header has no 'end_header' line within its first " + std::to_string(head.size()) +
                 " bytes");
}

// PLY: "element vertex N" / "element face M" lines up to end_header.
void CheckPlyHeader(const std::string& path, const std::string& head, uintmax_t size,
                    int64_t max_triangles) {
  if (head.compare(0, 3, "ply") != 0) return;
  CheckPlyHeaderEnd(path, head);
  const size_t end = head.find("end_header");
  if (end == std::string::npos) return;
  std::istringstream in(head.substr(0, end));
  std::string line;
  bool ascii = false;
  uint64_t vertices = 0, faces = 0, others = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string kind, name, count_token;
    words >> kind >> name >> count_token;
    if (kind == "format") ascii = name == "ascii";
    if (kind != "element") continue;
    uint64_t count = 0;
    if (!ParseCount(count_token, &count)) return;
    uint64_t& sum = name == "vertex" ? vertices : name == "face" ? faces : others;
    sum = std::min(sum + count, kCountCap);
  }
  const uint64_t body = size > end ? size - end : 0;
  CheckCountsFitFile(path, "PLY", vertices + others, faces, body, ascii ? 2 : 1,
                     max_triangles);
}

// Binary STL: 80-byte header, uint32 count, 50 bytes per triangle.
// Returns whether the file has the exact size of a binary STL.
bool CheckBinaryStl(const std::string& path, const std::string& head, uintmax_t size,
                    int64_t max_triangles) {
  if (head.size() < 84) return false;
  uint32_t count = 0;
  for (int i = 3; i >= 0; --i) count = (count << 8) | static_cast<unsigned char>(head[80 + i]);
  if (84 + 50 * static_cast<uint64_t>(count) != size) return false;
  if (count > static_cast<uint64_t>(max_triangles))
    Fail(path, "binary STL declares " + std::to_string(count) +
                   " triangles, more than max_triangles = " + std::to_string(max_triangles));
  return true;
}

std::string LowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

struct RawCounts {
  int64_t triangles = 0;   // after triangulation: sum of (n - 2) over polygons
  int64_t primitives = 0;  // points and lines, ignored
};

// Checks the scene as read, before post-processing: vertex welding compares
// with NaN-blind arithmetic and would merge NaN vertices into finite ones.
RawCounts CheckRawScene(const std::string& path, const aiScene& scene) {
  RawCounts counts;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    if (mesh.mNumVertices > 0 && mesh.mVertices == nullptr)
      Fail(path, "mesh " + std::to_string(m) + " has no vertex array (corrupt file)");
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        Fail(path, "non-finite coordinate (NaN or inf; assimp reads 32-bit floats) at vertex " +
                       std::to_string(v) + " of mesh " + std::to_string(m));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr)
        Fail(path, "face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                       " is empty (file shorter than its header says?)");
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices)
          Fail(path, "face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                         " uses vertex " + std::to_string(face.mIndices[k]) + " of only " +
                         std::to_string(mesh.mNumVertices));
      }
      if (face.mNumIndices >= 3)
        counts.triangles += face.mNumIndices - 2;
      else
        ++counts.primitives;
    }
  }
  return counts;
}

void CheckTriangleCount(const std::string& path, int64_t triangles, int64_t max_triangles) {
  if (triangles == 0) Fail(path, "no triangles (the file holds only points, lines or nothing)");
  if (triangles > max_triangles)
    Fail(path, std::to_string(triangles) + " triangles, more than max_triangles = " +
                   std::to_string(max_triangles));
}

// Exact-position key; +0.0 folds -0.0 into 0.0.
using PositionKey = std::array<double, 3>;
struct PositionHash {
  size_t operator()(const PositionKey& k) const {
    size_t h = 0;
    for (double x : k) h = h * 1000003u ^ std::hash<double>()(x);
    return h;
  }
};

// Edges whose two faces traverse them in the same direction (one face flipped).
int CountMisorientedEdges(const TriangleMesh& mesh, const MeshTopology& topo) {
  auto forward = [&](int f, const MeshEdge& e) {  // does face f run v0 -> v1?
    const Eigen::Vector3i& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] == e.v0 && t[(k + 1) % 3] == e.v1) return true;
    return false;
  };
  int count = 0;
  for (const MeshEdge& e : topo.edges)
    if (e.f1 >= 0 && forward(e.f0, e) == forward(e.f1, e)) ++count;
  return count;
}

double SignedVolume(const TriangleMesh& mesh) {
  double six_v = 0.0;
  for (const auto& t : mesh.triangles)
    six_v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  return six_v / 6.0;
}

}  // namespace

LoadedMesh LoadMesh(const std::string& path, const MeshLoadOptions& options) {
  CheckOptions(path, options);
  const int64_t max_triangles = std::min(options.max_triangles, kMaxIndexableTriangles);
  const uintmax_t size = CheckReadable(path);
  const std::string head = ReadPrefix(path, 1 << 16);
  CheckOffHeader(path, head, size, max_triangles);
  CheckPlyHeader(path, head, size, max_triangles);
  const bool binary_stl = CheckBinaryStl(path, head, size, max_triangles);

  AssimpMessages log;
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene == nullptr) {
    // assimp picks the reader by extension, then guesses from the content.
    const bool misnamed_stl = binary_stl && LowerExtension(path) != ".stl";
    Fail(path, std::string("assimp cannot read it: ") + importer.GetErrorString() +
                   (misnamed_stl ? " (the size fits a binary STL: name it *.stl)" : ""));
  }
  for (const std::string& m : log.messages()) {
    if (m.rfind("OFF:", 0) == 0) Fail(path, "assimp's OFF reader reported: " + m);
  }
  const RawCounts raw = CheckRawScene(path, *scene);
  CheckTriangleCount(path, raw.triangles, max_triangles);

  // DropNormals first so STL facet normals do not keep corners apart; assimp
  // welds within 1e-5 file units per sub-mesh, we weld exact positions after.
  scene = importer.ApplyPostProcessing(aiProcess_DropNormals | aiProcess_Triangulate |
                                       aiProcess_JoinIdenticalVertices |
                                       aiProcess_PreTransformVertices);
  if (scene == nullptr)
    Fail(path, std::string("assimp post-processing failed: ") + importer.GetErrorString());

  // Instanced meshes are duplicated by PreTransformVertices: count again.
  int64_t triangles = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) triangles += mesh.mFaces[f].mNumIndices == 3;
  }
  CheckTriangleCount(path, triangles, max_triangles);

  LoadedMesh out;
  for (const std::string& m : log.messages()) {
    // Materials do not matter for collision geometry.
    if (m.find("material") == std::string::npos) out.warnings.push_back(path + ": assimp: " + m);
  }
  TriangleMesh& mesh_M = out.mesh;
  mesh_M.name = path;
  mesh_M.triangles.reserve(static_cast<size_t>(triangles));
  std::unordered_map<PositionKey, int, PositionHash> welded;
  int num_repeated = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& in = *scene->mMeshes[m];
    // Weld in assimp's vertex order (the file's, for clean files), keeping
    // only vertices that triangles use.
    std::vector<int> index_of(in.mNumVertices, -1);  // assimp vertex -> welded vertex
    for (unsigned f = 0; f < in.mNumFaces; ++f) {
      const aiFace& face = in.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= in.mNumVertices)
          Fail(path, "assimp produced an out-of-range vertex index");
        index_of[face.mIndices[k]] = 0;
      }
    }
    for (unsigned i = 0; i < in.mNumVertices; ++i) {
      if (index_of[i] < 0) continue;
      const aiVector3D& p = in.mVertices[i];
      const Vector3 p_MV = options.scale * Vector3(p.x, p.y, p.z);
      if (!p_MV.allFinite()) Fail(path, "non-finite coordinate after node transforms and scale");
      if (p_MV.cwiseAbs().maxCoeff() > options.max_abs_coordinate)
        Fail(path, "coordinate " + Str(p_MV.cwiseAbs().maxCoeff()) + " m (after scale " +
                       Str(options.scale) + ") beyond max_abs_coordinate = " +
                       Str(options.max_abs_coordinate) + " m");
      const PositionKey key{p_MV.x() + 0.0, p_MV.y() + 0.0, p_MV.z() + 0.0};
      auto [it, inserted] = welded.emplace(key, mesh_M.num_vertices());
      if (inserted) mesh_M.vertices.push_back(p_MV);
      index_of[i] = it->second;
    }
    for (unsigned f = 0; f < in.mNumFaces; ++f) {
      const aiFace& face = in.mFaces[f];
      if (face.mNumIndices != 3) continue;
      const Eigen::Vector3i tri(index_of[face.mIndices[0]], index_of[face.mIndices[1]],
                                index_of[face.mIndices[2]]);
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
        ++num_repeated;
        continue;
      }
      mesh_M.triangles.push_back(tri);
    }
  }
  if (mesh_M.triangles.empty())
    Fail(path, "no triangles left after dropping " + std::to_string(num_repeated) +
                   " degenerate ones (repeated vertex)");

  if (raw.primitives > 0)
    out.warnings.push_back(path + ": ignored " + std::to_string(raw.primitives) +
                           " point/line primitives");
  if (num_repeated > 0)
    out.warnings.push_back(path + ": dropped " + std::to_string(num_repeated) +
                           " degenerate triangles (repeated vertex after welding)");
  out.topology = ComputeTopology(mesh_M);
  if (out.topology.num_degenerate_triangles > 0)
    out.warnings.push_back(path + ": " + std::to_string(out.topology.num_degenerate_triangles) +
                           " zero-area triangles kept");
  if (!out.topology.closed())
    out.warnings.push_back(path + " is " + out.topology.Describe() +
                           "; penetration depth works on it, containment tests need a closed mesh");
  // Contact normals and containment assume outward counter-clockwise faces.
  const int misoriented = CountMisorientedEdges(mesh_M, out.topology);
  if (misoriented > 0)
    out.warnings.push_back(path + ": faces are inconsistently oriented across " +
                           std::to_string(misoriented) + " edges");
  else if (out.topology.closed() && SignedVolume(mesh_M) < 0.0)
    out.warnings.push_back(path + ": closed but faces point inward (negative volume)");
  return out;
}

}  // namespace pd
