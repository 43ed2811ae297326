#include "haptics/scene/build_scene.h"

#include <spdlog/spdlog.h>

#include <map>
#include <stdexcept>
#include <type_traits>

#include "pd_core/mesh/load_mesh.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/mesh/model_cache.h"

namespace haptics {
namespace {

// Above this many triangles per model a 1 kHz loop is unlikely to hold.
constexpr int kTriangleBudget = 20000;

template <typename S>
constexpr bool kIsPrimitive =
    std::is_same_v<S, PlaneShape> || std::is_same_v<S, SphereShape> || std::is_same_v<S, BoxShape> ||
    std::is_same_v<S, CapsuleShape> || std::is_same_v<S, CylinderShape>;

pd::TriangleMesh MakeVariantMesh(const ShapeVariant& v) {
  return std::visit(
      [](const auto& s) -> pd::TriangleMesh {
        using S = std::decay_t<decltype(s)>;
        if constexpr (kIsPrimitive<S>) {
          throw std::invalid_argument("a primitive shape has no mesh");
        } else if constexpr (std::is_same_v<S, MeshFileShape>) {
          pd::MeshLoadOptions options;
          options.scale = s.scale;
          options.max_triangles = s.max_triangles;
          pd::LoadedMesh loaded = pd::LoadMesh(s.path, options);
          for (const std::string& w : loaded.warnings) spdlog::warn("{}", w);
          return std::move(loaded.mesh);
        } else if constexpr (std::is_same_v<S, IcosphereShape>) {
          return pd::MakeIcosphere(s.radius, s.subdivisions);
        } else if constexpr (std::is_same_v<S, TorusShape>) {
          return pd::MakeTorus(s.major_radius, s.minor_radius, s.major_segments, s.minor_segments);
        } else if constexpr (std::is_same_v<S, USlotShape>) {
          return pd::MakeUSlot(s.half_extents, s.slot_width, s.slot_depth);
        } else if constexpr (std::is_same_v<S, ThinPlateShape>) {
          return pd::MakeThinPlate(s.half_x, s.half_y, s.half_thickness);
        } else if constexpr (std::is_same_v<S, CupShape>) {
          return pd::MakeCup(s.outer_radius, s.height, s.wall_thickness, s.floor_thickness,
                             s.segments);
        } else if constexpr (std::is_same_v<S, BlockWithHoleShape>) {
          return pd::MakeBlockWithHole(s.half_extents, s.hole_half_width, s.round, s.segments);
        } else if constexpr (std::is_same_v<S, LRodShape>) {
          return pd::MakeLRod(s.arm_x, s.arm_y, s.width, s.thickness);
        } else {
          static_assert(std::is_same_v<S, SpoonShape>);
          return pd::MakeSpoon(s.dims);
        }
      },
      v);
}

// The primitive's geometry, or null for a mesh-type shape.
std::shared_ptr<const pd::Geometry> MakePrimitive(const ShapeVariant& v) {
  return std::visit(
      [](const auto& s) -> std::shared_ptr<const pd::Geometry> {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, PlaneShape>) return pd::Geometry::MakeHalfSpace();
        if constexpr (std::is_same_v<S, SphereShape>) return pd::Geometry::MakeSphere(s.radius);
        if constexpr (std::is_same_v<S, BoxShape>) return pd::Geometry::MakeBox(s.half_extents);
        if constexpr (std::is_same_v<S, CapsuleShape>)
          return pd::Geometry::MakeCapsule(s.radius, 0.5 * s.length);
        if constexpr (std::is_same_v<S, CylinderShape>)
          return pd::Geometry::MakeCylinder(s.radius, 0.5 * s.length);
        return nullptr;
      },
      v);
}

std::shared_ptr<const pd::CollisionModel> BuildModel(pd::TriangleMesh mesh, const ShapeConfig& shape,
                                                     const std::string& config_file,
                                                     const std::string& cache_dir) {
  if (mesh.num_triangles() > kTriangleBudget)
    spdlog::warn("{}: {}: {} triangles; more than {} may not hold the loop rate with contact.geometry_thread off", config_file,
                 shape.key, mesh.num_triangles(), kTriangleBudget);
  pd::ModelCacheReport cache;
  auto model = pd::BuildCollisionModelCached(std::move(mesh), cache_dir, &cache);
  if (!cache.problem.empty()) spdlog::warn("{}: {}: model cache: {}", config_file, shape.key, cache.problem);
  if (cache.outcome != pd::ModelCacheOutcome::kDisabled)
    spdlog::debug("{}: {}: model cache {}: {}", config_file, shape.key,
                  pd::ModelCacheOutcomeName(cache.outcome), cache.path);
  if (!model->closed())
    spdlog::warn("{}: {}: mesh is {}; containment (a tool wholly inside) is not detected",
                 config_file, shape.key, model->topology().Describe());
  return model;
}

bool DeclaredConvex(const ShapeConfig& shape) {
  const auto* file = std::get_if<MeshFileShape>(&shape.shape);
  return file != nullptr && file->convex;
}

}  // namespace

pd::TriangleMesh MakeShapeMesh(const ShapeConfig& shape, const std::string& config_file) {
  try {
    return MakeVariantMesh(shape.shape);
  } catch (const pd::MeshLoadError& e) {
    throw ConfigError(config_file, shape.key, e.what());
  } catch (const std::invalid_argument& e) {
    throw ConfigError(config_file, shape.key, e.what());
  }
}

std::shared_ptr<const pd::Geometry> MakeShapeGeometry(const ShapeConfig& shape,
                                                      const std::string& config_file,
                                                      const std::string& cache_dir,
                                                      SharedGeometries* shared) {
  try {
    if (auto primitive = MakePrimitive(shape.shape)) return primitive;
  } catch (const std::invalid_argument& e) {
    throw ConfigError(config_file, shape.key, e.what());
  }
  pd::TriangleMesh mesh = MakeShapeMesh(shape, config_file);
  std::string key;
  if (shared != nullptr) {
    key = pd::ModelCacheKey(mesh) + (DeclaredConvex(shape) ? "/convex" : "/general");
    if (const auto it = shared->find(key); it != shared->end()) return it->second;
  }
  auto model = BuildModel(std::move(mesh), shape, config_file, cache_dir);
  std::shared_ptr<const pd::Geometry> geometry;
  try {
    geometry = DeclaredConvex(shape) ? pd::Geometry::MakeConvexMesh(std::move(model))
                                     : pd::Geometry::MakeMesh(std::move(model));
  } catch (const pd::NotConvexError& e) {
    throw ConfigError(config_file, shape.key + ".convex",
                      "mesh '" + std::get<MeshFileShape>(shape.shape).path +
                          "' is declared convex but is not: " + e.what() +
                          " (set convex: false to use it as a general mesh)");
  }
  if (shared != nullptr) shared->emplace(key, geometry);
  return geometry;
}

SceneModels BuildSceneModels(const SceneConfig& config, const std::string& cache_dir) {
  const std::string& cache = cache_dir.empty() ? config.cache_dir : cache_dir;
  if (std::holds_alternative<PlaneShape>(config.tool.shape.shape))
    throw ConfigError(config.file, config.tool.shape.key + ".type",
                      "'plane' is unbounded and cannot be the tool");
  SceneModels models;
  SharedGeometries shared;  // identical meshes are built once
  models.tool = MakeShapeGeometry(config.tool.shape, config.file, cache, &shared);
  models.X_TG = config.tool.X_TG;
  for (const ObjectConfig& object : config.objects)
    models.objects.push_back(
        {object.name, MakeShapeGeometry(object.shape, config.file, cache, &shared), object.X_WS});
  return models;
}

}  // namespace haptics
