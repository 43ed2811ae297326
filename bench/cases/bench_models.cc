#include "bench/cases/bench_models.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "bench/common/stats.h"
#include "pd_core/mesh/load_mesh.h"
#include "pd_core/geometry/make_shapes.h"

namespace pd_bench {

std::vector<PairSpec> DefaultPairs() {
  return {
      {"torus_knot_3k", "procedural:torus_knot_2_3", "procedural:torus_knot_2_3", true},
      {"knot1_6k", "knot1.off", "knot1.off", true},
      {"cow_cow", "cow.off", "cow.off", true},
      {"camel_cow", "camel.off", "cow.off", false},
      {"dragon_dragon", "ChineseDragon-10kv.off", "ChineseDragon-10kv.off", false},
      {"armadillo_bunny", "armadillo.off", "bunny00.off", false},
      // Cold queries (issue 13): more closed real meshes of 2k-10k triangles,
      // random scenario only.
      {"elephant_cow", "elephant.off", "cow.off", false, true},
      {"dino_femur", "dino.off", "femur.off", false, true},
      {"homer_triceratops", "homer.off", "triceratops.off", false, true},
      {"elk_hand", "elk.off", "hand.off", false, true},
      {"anchor_knot", "anchor_dense.off", "knot.off", false, true},
      {"bones_coupling", "bones.off", "couplingdown.off", false, true},
      {"rotor_blobby", "rotor_small.off", "blobby.off", false, true},
  };
}

namespace {

pd::TriangleMesh Procedural(const std::string& name) {
  // Sizes are arbitrary here: Normalise() rescales every model.
  if (name == "procedural:torus_knot_2_3") return pd::MakeTorusKnot(2, 3, 0.2, 1.0);
  if (name == "procedural:torus_100k") return pd::MakeTorus(1.0, 0.3, 400, 125);
  if (name == "procedural:icosphere_82k") return pd::MakeIcosphere(1.0, 6);
  throw std::invalid_argument("unknown procedural model " + name);
}

}  // namespace

ModelCache::ModelCache(std::string mesh_dir, int build_repeats)
    : mesh_dir_(std::move(mesh_dir)), build_repeats_(std::max(1, build_repeats)) {}

std::shared_ptr<const ModelInfo> ModelCache::Get(const std::string& name, std::string* why,
                                                 double radius) {
  const std::string key =
      radius == kModelRadius ? name : name + "@" + std::to_string(radius).substr(0, 6) + "m";
  if (auto it = models_.find(key); it != models_.end()) return it->second;
  auto info = std::make_shared<ModelInfo>();
  info->name = key;
  pd::TriangleMesh mesh;
  if (name.rfind("procedural:", 0) == 0) {
    info->source = "procedural";
    mesh = Procedural(name);
  } else {
    const std::string path = (std::filesystem::path(mesh_dir_) / name).string();
    info->source = path;
    if (!std::filesystem::exists(path)) {
      *why = path + " is missing (run scripts/fetch_meshes.sh)";
      return nullptr;
    }
    try {
      mesh = pd::LoadMesh(path).mesh;
    } catch (const std::exception& e) {
      *why = e.what();
      return nullptr;
    }
  }
  // Normalise to a common radius about the bounding-box centre (the centre
  // CollisionModel uses), so relative tolerances mean the same for all pairs.
  const pd::MeshBounds bounds = pd::ComputeBounds(mesh);
  double r = 0.0;
  for (const pd::Vector3& v : mesh.vertices) r = std::max(r, (v - bounds.center()).norm());
  info->scale = radius / r;
  for (pd::Vector3& v : mesh.vertices) v *= info->scale;
  info->triangles = mesh.num_triangles();

  std::vector<double> build_ms;
  for (int i = 0; i < build_repeats_; ++i) {
    pd::TriangleMesh copy = mesh;  // Build takes the mesh by value: copy outside the clock
    const auto t0 = std::chrono::steady_clock::now();
    info->model = pd::CollisionModel::Build(std::move(copy));
    build_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  info->build_ms = Percentile(build_ms, 50);
  info->memory_bytes = info->model->MemoryBytes();
  info->closed = info->model->closed();
  models_[key] = info;
  return info;
}

std::vector<std::shared_ptr<const ModelInfo>> ModelCache::All() const {
  std::vector<std::shared_ptr<const ModelInfo>> all;
  for (const auto& [name, info] : models_) all.push_back(info);
  std::sort(all.begin(), all.end(),
            [](const auto& a, const auto& b) { return a->triangles < b->triangles; });
  return all;
}

}  // namespace pd_bench
