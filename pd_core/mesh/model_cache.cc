#include "pd_core/mesh/model_cache.h"

#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

namespace pd {

// Reads and writes every field of CollisionModel and Bvh (friend of both).
struct ModelCacheAccess;

namespace {

constexpr char kMagic[8] = {'P', 'D', 'M', 'O', 'D', 'E', 'L', '\0'};
// Bump when CollisionModel, Bvh, MeshTopology or this layout changes.
constexpr uint32_t kFormatVersion = 5;  // 2: component_vertices_; 3: surface-area-split BVH; 4: inner_spheres_; 5: BvhNode bounds
constexpr size_t kHeaderBytes = sizeof(kMagic) + 4 + 8 + 4;  // magic, version, payload size, crc

uint32_t Crc32(const void* data, size_t bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  const auto* p = static_cast<const Bytef*>(data);
  while (bytes > 0) {  // zlib takes uInt lengths
    const uInt chunk = static_cast<uInt>(std::min<size_t>(bytes, 1u << 30));
    crc = crc32(crc, p, chunk);
    p += chunk;
    bytes -= chunk;
  }
  return static_cast<uint32_t>(crc);
}

// Plain bytes of fixed-size values: ints, doubles, Eigen fixed-size vectors
// and matrices (plain arrays of doubles, no padding), BvhNode, MeshEdge.
class ByteWriter {
 public:
  template <typename T>
  void Put(const T& value) {
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <typename T>
  void PutVector(const std::vector<T>& v) {
    Put<uint64_t>(v.size());
    const auto* p = reinterpret_cast<const char*>(v.data());
    bytes_.insert(bytes_.end(), p, p + v.size() * sizeof(T));
  }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  std::vector<char> bytes_;
};

// Bounds-checked reads: any overrun sets ok() false and yields zeros.
class ByteReader {
 public:
  ByteReader(const char* data, size_t size) : data_(data), size_(size) {}
  template <typename T>
  T Get() {
    T value{};
    if (!ok_ || size_ - at_ < sizeof(T)) {
      ok_ = false;
      return value;
    }
    std::memcpy(&value, data_ + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  template <typename T>
  bool GetVector(std::vector<T>* v) {
    const uint64_t n = Get<uint64_t>();
    if (!ok_ || n > (size_ - at_) / sizeof(T)) return ok_ = false;
    v->resize(n);
    std::memcpy(v->data(), data_ + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return true;
  }
  bool ok() const { return ok_; }
  bool at_end() const { return at_ == size_; }

 private:
  const char* data_;
  size_t size_;
  size_t at_ = 0;
  bool ok_ = true;
};

template <typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

std::string Hex(uint32_t v) {
  char buf[9];
  std::snprintf(buf, sizeof buf, "%08x", v);
  return buf;
}

}  // namespace

struct ModelCacheAccess {
  static std::vector<char> Serialize(const CollisionModel& m) {
    ByteWriter w;
    w.PutVector(m.mesh_.vertices);
    w.PutVector(m.mesh_.triangles);
    const MeshTopology& t = m.topology_;
    w.PutVector(t.edges);
    w.PutVector(t.triangle_edges);
    w.Put<int32_t>(t.num_boundary_edges);
    w.Put<int32_t>(t.num_nonmanifold_edges);
    w.Put<int32_t>(t.num_degenerate_triangles);
    w.PutVector(m.bvh_.nodes_);
    w.PutVector(m.bvh_.order_);
    w.Put<int32_t>(m.bvh_.depth_);
    w.PutVector(m.face_normals_);
    w.Put(m.center_M_);
    w.Put(m.radius_);
    w.Put(m.centroid_M_);
    w.PutVector(m.support_dirs_M_);
    w.PutVector(m.support_values_);
    w.PutVector(m.hull_vertices_);
    w.PutVector(m.owned_features_);
    w.PutVector(m.component_vertices_);
    w.PutVector(m.inner_spheres_);
    return w.bytes();
  }

  // The model stored in `payload` for exactly `mesh`, or null with *problem.
  static std::shared_ptr<CollisionModel> Deserialize(const char* payload, size_t size,
                                                     const TriangleMesh& mesh, std::string* problem) {
    std::shared_ptr<CollisionModel> m(new CollisionModel());
    ByteReader r(payload, size);
    r.GetVector(&m->mesh_.vertices);
    r.GetVector(&m->mesh_.triangles);
    if (!r.ok() || !SameBytes(m->mesh_.vertices, mesh.vertices) ||
        !SameBytes(m->mesh_.triangles, mesh.triangles)) {
      *problem = "stored mesh differs from the mesh asked for";
      return nullptr;
    }
    m->mesh_.name = mesh.name;
    MeshTopology& t = m->topology_;
    r.GetVector(&t.edges);
    r.GetVector(&t.triangle_edges);
    t.num_boundary_edges = r.Get<int32_t>();
    t.num_nonmanifold_edges = r.Get<int32_t>();
    t.num_degenerate_triangles = r.Get<int32_t>();
    r.GetVector(&m->bvh_.nodes_);
    r.GetVector(&m->bvh_.order_);
    r.Get<int32_t>();  // stored depth: measured from the links below instead
    r.GetVector(&m->face_normals_);
    m->center_M_ = r.Get<Vector3>();
    m->radius_ = r.Get<double>();
    m->centroid_M_ = r.Get<Vector3>();
    r.GetVector(&m->support_dirs_M_);
    r.GetVector(&m->support_values_);
    r.GetVector(&m->hull_vertices_);
    r.GetVector(&m->owned_features_);
    r.GetVector(&m->component_vertices_);
    r.GetVector(&m->inner_spheres_);
    if (!r.ok() || !r.at_end()) {
      *problem = "payload does not parse (truncated or wrong layout)";
      return nullptr;
    }
    if (!InBounds(*m, problem)) return nullptr;
    // Traversal stacks are sized by the depth: never trust the file's.
    m->bvh_.depth_ = Bvh::MeasureDepth(m->bvh_.nodes_);
    Bvh::DeriveBounds(&m->bvh_.nodes_);
    return m;
  }

  // Every index in range and every per-triangle array sized: a file that
  // passed the CRC but was written by a buggy build still cannot make a
  // query read out of bounds.
  static bool InBounds(const CollisionModel& m, std::string* problem) {
    const int nv = m.mesh_.num_vertices(), nt = m.mesh_.num_triangles();
    const int ne = static_cast<int>(m.topology_.edges.size());
    const int nn = static_cast<int>(m.bvh_.nodes_.size());
    auto fail = [&](const char* what) {
      *problem = std::string("inconsistent ") + what;
      return false;
    };
    if (static_cast<int>(m.topology_.triangle_edges.size()) != nt ||
        static_cast<int>(m.face_normals_.size()) != nt ||
        static_cast<int>(m.owned_features_.size()) != nt ||
        static_cast<int>(m.bvh_.order_.size()) != nt)
      return fail("per-triangle array sizes");
    for (const MeshEdge& e : m.topology_.edges)
      if (e.v0 < 0 || e.v0 >= nv || e.v1 < 0 || e.v1 >= nv || e.f0 < 0 || e.f0 >= nt || e.f1 < -1 ||
          e.f1 >= nt)
        return fail("edges");
    for (const auto& te : m.topology_.triangle_edges)
      for (int e : te)
        if (e < 0 || e >= ne) return fail("triangle edges");
    for (int32_t t : m.bvh_.order_)
      if (t < 0 || t >= nt) return fail("BVH triangle order");
    for (int i = 0; i < nn; ++i) {
      const BvhNode& node = m.bvh_.nodes_[i];
      if (node.count < 0) return fail("BVH node");
      if (node.is_leaf()) {
        if (node.right_or_first < 0 || node.right_or_first + node.count > nt) return fail("BVH leaf");
      } else if (i + 1 >= nn || node.right_or_first <= i || node.right_or_first >= nn) {
        return fail("BVH children");
      }
    }
    if ((nt > 0) != (nn > 0)) return fail("BVH size");
    if (m.support_dirs_M_.size() != m.support_values_.size()) return fail("support samples");
    for (int v : m.hull_vertices_)
      if (v < 0 || v >= nv) return fail("hull vertices");
    for (int v : m.component_vertices_)
      if (v < 0 || v >= nv) return fail("component vertices");
    if ((nt > 0) != !m.component_vertices_.empty()) return fail("component vertices");
    // An inner sphere proves collisions: a stored one must be a real ball of
    // a closed model (a wrong one would report contact where there is none).
    if (!m.inner_spheres_.empty() && !m.topology_.closed()) return fail("inner spheres");
    for (const InnerSphere& s : m.inner_spheres_)
      if (!s.p_MC.allFinite() || !(s.radius > 0.0) || !std::isfinite(s.radius))
        return fail("inner spheres");
    return true;
  }
};

const char* ModelCacheOutcomeName(ModelCacheOutcome outcome) {
  switch (outcome) {
    case ModelCacheOutcome::kDisabled: return "disabled";
    case ModelCacheOutcome::kHit: return "hit";
    case ModelCacheOutcome::kMiss: return "miss";
    case ModelCacheOutcome::kRejected: return "rejected";
  }
  return "?";
}

std::string ModelCacheKey(const TriangleMesh& mesh) {
  const uint32_t crc_v = Crc32(mesh.vertices.data(), mesh.vertices.size() * sizeof(Vector3));
  const uint32_t crc_t =
      Crc32(mesh.triangles.data(), mesh.triangles.size() * sizeof(Eigen::Vector3i));
  return Hex(crc_v) + "-" + Hex(crc_t) + "-" + std::to_string(mesh.num_vertices()) + "-" +
         std::to_string(mesh.num_triangles()) + "-v" + std::to_string(kFormatVersion);
}

namespace {

// The model in `path` for `mesh`; null with *problem if the file is absent
// (problem left empty) or fails any check.
std::shared_ptr<const CollisionModel> ReadCacheFile(const std::string& path,
                                                    const TriangleMesh& mesh, std::string* problem) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return nullptr;
  const std::streamoff end = in.tellg();
  if (end < 0) {
    *problem = "cannot read the file";
    return nullptr;
  }
  std::vector<char> file(static_cast<size_t>(end));
  in.seekg(0);
  if (!in.read(file.data(), end)) {
    *problem = "cannot read the file";
    return nullptr;
  }
  if (file.size() < kHeaderBytes) {
    *problem = "truncated header (" + std::to_string(file.size()) + " bytes)";
    return nullptr;
  }
  ByteReader header(file.data(), kHeaderBytes);
  char magic[sizeof(kMagic)];
  for (char& c : magic) c = header.Get<char>();
  const uint32_t version = header.Get<uint32_t>();
  const uint64_t payload_size = header.Get<uint64_t>();
  const uint32_t crc = header.Get<uint32_t>();
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
    *problem = "not a model cache file (bad magic)";
    return nullptr;
  }
  if (version != kFormatVersion) {
    *problem = "format version " + std::to_string(version) + ", expected " +
               std::to_string(kFormatVersion);
    return nullptr;
  }
  if (payload_size != file.size() - kHeaderBytes) {
    *problem = "size mismatch: header says " + std::to_string(payload_size) + " payload bytes, file has " +
               std::to_string(file.size() - kHeaderBytes);
    return nullptr;
  }
  const char* payload = file.data() + kHeaderBytes;
  if (Crc32(payload, payload_size) != crc) {
    *problem = "checksum mismatch (corrupt file)";
    return nullptr;
  }
  return ModelCacheAccess::Deserialize(payload, payload_size, mesh, problem);
}

// Writes atomically (temporary file + rename); "" on success, else why not.
std::string WriteCacheFile(const std::string& path, const CollisionModel& model) {
  const std::vector<char> payload = ModelCacheAccess::Serialize(model);
  ByteWriter header;
  for (char c : kMagic) header.Put(c);
  header.Put<uint32_t>(kFormatVersion);
  header.Put<uint64_t>(payload.size());
  header.Put<uint32_t>(Crc32(payload.data(), payload.size()));
  static thread_local std::mt19937_64 rng(std::random_device{}());
  const std::string tmp = path + ".tmp" + std::to_string(rng());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(header.bytes().data(), static_cast<std::streamsize>(header.bytes().size()));
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      return "cannot write " + tmp;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    return "cannot rename " + tmp + " to " + path + ": " + ec.message();
  }
  return "";
}

}  // namespace

std::shared_ptr<const CollisionModel> BuildCollisionModelCached(TriangleMesh mesh,
                                                                const std::string& cache_dir,
                                                                ModelCacheReport* report) {
  ModelCacheReport local;
  ModelCacheReport& rep = report ? *report : local;
  rep = ModelCacheReport{};
  if (cache_dir.empty()) return CollisionModel::Build(std::move(mesh));

  rep.path = (std::filesystem::path(cache_dir) / (ModelCacheKey(mesh) + ".pdmodel")).string();
  std::string problem;
  if (auto cached = ReadCacheFile(rep.path, mesh, &problem)) {
    rep.outcome = ModelCacheOutcome::kHit;
    return cached;
  }
  rep.outcome = problem.empty() ? ModelCacheOutcome::kMiss : ModelCacheOutcome::kRejected;
  if (!problem.empty()) rep.problem = rep.path + ": " + problem + "; rebuilt";
  auto model = CollisionModel::Build(std::move(mesh));
  std::error_code ec;
  std::filesystem::create_directories(cache_dir, ec);
  std::string write_problem =
      ec ? "cannot create cache directory " + cache_dir + ": " + ec.message() : WriteCacheFile(rep.path, *model);
  if (!write_problem.empty())
    rep.problem += (rep.problem.empty() ? "" : "; ") + write_problem;
  return model;
}

}  // namespace pd
