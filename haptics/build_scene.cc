#include "haptics/build_scene.h"

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <type_traits>

#include "pd_core/load_mesh.h"
#include "pd_core/make_shapes.h"

namespace haptics {
namespace {

// Above this many triangles per model a 1 kHz loop is unlikely to hold.
constexpr int kTriangleBudget = 20000;

pd::TriangleMesh MakeVariant(const ShapeVariant& v) {
  return std::visit(
      [](const auto& s) -> pd::TriangleMesh {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, MeshFileShape>) {
          pd::MeshLoadOptions options;
          options.scale = s.scale;
          pd::LoadedMesh loaded = pd::LoadMesh(s.path, options);
          for (const std::string& w : loaded.warnings) spdlog::warn("{}", w);
          return std::move(loaded.mesh);
        } else if constexpr (std::is_same_v<S, BoxShape>) {
          return pd::MakeBox(s.half_extents);
        } else if constexpr (std::is_same_v<S, IcosphereShape>) {
          return pd::MakeIcosphere(s.radius, s.subdivisions);
        } else if constexpr (std::is_same_v<S, CylinderShape>) {
          return pd::MakeCylinder(s.radius, s.length, s.segments);
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

std::shared_ptr<const pd::CollisionModel> BuildModel(pd::TriangleMesh mesh, const ShapeConfig& shape,
                                                     const std::string& config_file) {
  if (mesh.num_triangles() > kTriangleBudget)
    spdlog::warn("{}: {}: {} triangles; more than {} may not hold the loop rate", config_file,
                 shape.key, mesh.num_triangles(), kTriangleBudget);
  auto model = pd::CollisionModel::Build(std::move(mesh));
  if (!model->closed())
    spdlog::warn("{}: {}: mesh is {}; containment (a tool wholly inside) is not detected",
                 config_file, shape.key, model->topology().Describe());
  return model;
}

}  // namespace

pd::TriangleMesh MakeShapeMesh(const ShapeConfig& shape, const std::string& config_file) {
  try {
    return MakeVariant(shape.shape);
  } catch (const pd::MeshLoadError& e) {
    throw ConfigError(config_file, shape.key, e.what());
  } catch (const std::invalid_argument& e) {
    throw ConfigError(config_file, shape.key, e.what());
  }
}

SceneModels BuildSceneModels(const SceneConfig& config) {
  SceneModels models;
  pd::TriangleMesh tool = MakeShapeMesh(config.tool.shape, config.file);
  for (pd::Vector3& p_G : tool.vertices) p_G = config.tool.X_TG * p_G;  // now p_T
  models.tool = BuildModel(std::move(tool), config.tool.shape, config.file);
  for (const ObjectConfig& object : config.objects) {
    models.objects.push_back(
        {object.name, BuildModel(MakeShapeMesh(object.shape, config.file), object.shape, config.file),
         object.X_WS});
  }
  return models;
}

}  // namespace haptics
