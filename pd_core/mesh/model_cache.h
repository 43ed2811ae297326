#pragma once
// Disk cache of CollisionModel precomputation (topology, face normals, BVH,
// bounding sphere, support samples, hull candidates, feature ownership, one
// vertex per connected component), keyed by the mesh's content: the CRC-32s
// of its vertex and triangle bytes, their counts and the format version. A
// cache file is only used if every check passes: magic, version, size,
// payload CRC-32, structural bounds, and the stored mesh equal byte for byte
// to the one asked for. Anything else (truncated, corrupt, from another mesh
// or version) is reported and the model rebuilt and rewritten; a cache file
// is never trusted blindly.
// Files are written to a temporary name and renamed, so readers never see a
// half-written file.
#include <memory>
#include <string>

#include "pd_core/mesh/collision_model.h"
#include "pd_core/mesh/mesh.h"

namespace pd {

enum class ModelCacheOutcome {
  kDisabled,  // cache_dir empty: built, nothing stored
  kHit,       // loaded from a valid cache file
  kMiss,      // no cache file: built and stored
  kRejected,  // a cache file existed but failed a check: rebuilt and stored
};
const char* ModelCacheOutcomeName(ModelCacheOutcome outcome);

struct ModelCacheReport {
  ModelCacheOutcome outcome = ModelCacheOutcome::kDisabled;
  std::string path;     // the cache file for this mesh ("" when disabled)
  std::string problem;  // why a file was rejected or could not be written ("" if none)
};

// "<crc32 of vertex bytes>-<crc32 of triangle bytes>-<nv>-<nt>-v<version>".
std::string ModelCacheKey(const TriangleMesh& mesh);

// CollisionModel::Build(mesh), or the same model read from
// cache_dir/<key>.pdmodel. The directory is created if needed. Failure to
// write is not an error (the model is still returned; report->problem says
// why). The caller logs report->problem.
std::shared_ptr<const CollisionModel> BuildCollisionModelCached(TriangleMesh mesh,
                                                                const std::string& cache_dir,
                                                                ModelCacheReport* report = nullptr);

}  // namespace pd
