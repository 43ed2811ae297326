#pragma once
// The benchmark's model pairs: loading, size normalisation and precomputation
// cost (CollisionModel::Build time and memory) of each model.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pd_core/mesh/collision_model.h"

namespace pd_bench {

// Every model is scaled so its bounding-sphere radius is this (m): probe and
// scene then have the same size, about that of a hand-held object.
inline constexpr double kModelRadius = 0.1;

struct ModelInfo {
  std::string name;      // file name or generator
  std::string source;    // path or "procedural"
  double scale = 1.0;    // file units -> metres
  int triangles = 0;
  bool closed = false;
  double build_ms = 0.0;      // CollisionModel::Build wall time (median of repeats)
  size_t memory_bytes = 0;    // CollisionModel::MemoryBytes()
  std::shared_ptr<const pd::CollisionModel> model;
};

struct PairSpec {
  std::string name;
  std::string probe, scene;  // file names in the mesh dir, or "procedural:..." names
  bool in_quick = false;     // part of the --quick run
  bool random_only = false;  // only the random (cold) scenario
};

struct BenchPair {
  std::string name;
  std::shared_ptr<const ModelInfo> probe, scene;
  bool random_only = false;  // PairSpec::random_only
};

// Pairs of increasing size.
std::vector<PairSpec> DefaultPairs();

// Loads, normalises and builds models by name, each once. Procedural names:
// "procedural:torus_knot_2_3" (3k tris), "procedural:torus_100k",
// "procedural:icosphere_82k".
class ModelCache {
 public:
  ModelCache(std::string mesh_dir, int build_repeats);
  // nullptr and *why set when the file is missing or unreadable. `radius`:
  // the bounding-sphere radius the model is scaled to (m).
  std::shared_ptr<const ModelInfo> Get(const std::string& name, std::string* why,
                                       double radius = kModelRadius);
  std::vector<std::shared_ptr<const ModelInfo>> All() const;

 private:
  std::string mesh_dir_;
  int build_repeats_;
  std::map<std::string, std::shared_ptr<const ModelInfo>> models_;
};

}  // namespace pd_bench
