#include "haptics/scene/shape_config_reader.h"

#include <filesystem>

namespace haptics {
namespace {

// Sizes: up to 10 m; haptic scenes are centimetres, but meshes of rooms load.
const Range kLength = Range::Positive(10.0, "m");
const Range kLengthOrZero = Range::NonNegative(10.0, "m");

ShapeVariant ReadVariant(const YamlMap& m, const std::string& type, const std::string& config_dir) {
  if (type == "mesh") {
    MeshFileShape s;
    const std::string file = m.String("file");
    std::filesystem::path path(file);
    if (path.is_relative()) path = std::filesystem::path(config_dir) / path;
    s.path = path.lexically_normal().string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(s.path, ec))
      m.source().Fail(m.Path("file"), "mesh file '" + s.path + "' does not exist (relative paths are "
                                      "resolved against the config file's directory)");
    s.scale = m.NumberOr("scale", 1.0, Range::Positive(1000.0, ""));
    s.max_triangles = m.IntegerOr("max_triangles", s.max_triangles, 1, 50'000'000);
    if (m.Has("convex")) s.convex = m.Choice("convex", {"true", "false"}) == "true";
    return s;
  }
  if (type == "plane") return PlaneShape{};
  if (type == "sphere") return SphereShape{m.Number("radius", kLength)};
  if (type == "box") return BoxShape{m.Vector("half_extents", kLength)};
  if (type == "capsule")
    return CapsuleShape{m.Number("radius", kLength), m.Number("length", kLengthOrZero)};
  if (type == "cylinder") {
    if (m.Has("segments")) {
      m.IntegerOr("segments", 32, 3, 512);  // still range-checked: old configs stay valid
      m.source().Warn(m.Path("segments"),
                      "ignored: the cylinder is now an exact primitive (remove the key)");
    }
    return CylinderShape{m.Number("radius", kLength), m.Number("length", kLength)};
  }
  if (type == "icosphere")
    return IcosphereShape{m.Number("radius", kLength), m.IntegerOr("subdivisions", 2, 0, 5)};
  if (type == "torus")
    return TorusShape{m.Number("major_radius", kLength), m.Number("minor_radius", kLength),
                      m.IntegerOr("major_segments", 32, 3, 512),
                      m.IntegerOr("minor_segments", 16, 3, 512)};
  if (type == "u_slot")
    return USlotShape{m.Vector("half_extents", kLength), m.Number("slot_width", kLength),
                      m.Number("slot_depth", kLength)};
  if (type == "thin_plate")
    return ThinPlateShape{m.Number("half_x", kLength), m.Number("half_y", kLength),
                          m.Number("half_thickness", kLength)};
  if (type == "cup")
    return CupShape{m.Number("outer_radius", kLength), m.Number("height", kLength),
                    m.Number("wall_thickness", kLength), m.Number("floor_thickness", kLength),
                    m.IntegerOr("segments", 32, 3, 512)};
  if (type == "block_with_hole") {
    const bool round = m.Choice("hole", {"round", "square"}) == "round";
    return BlockWithHoleShape{m.Vector("half_extents", kLength), m.Number("hole_half_width", kLength),
                              round, m.IntegerOr("segments", round ? 32 : 4, 4, 512)};
  }
  if (type == "l_rod")
    return LRodShape{m.Number("arm_x", kLength), m.Number("arm_y", kLength),
                     m.Number("width", kLength), m.Number("thickness", kLength)};
  if (type == "spoon") {
    SpoonShape s;
    s.dims.length = m.Number("length", kLength);
    s.dims.handle_width = m.Number("handle_width", kLength);
    s.dims.bowl_length = m.Number("bowl_length", kLength);
    s.dims.bowl_width = m.Number("bowl_width", kLength);
    s.dims.bowl_depth = m.Number("bowl_depth", kLength);
    s.dims.thickness = m.Number("thickness", kLength);
    s.dims.segments_along = m.IntegerOr("segments_along", 8, 4, 256);
    s.dims.segments_across = m.IntegerOr("segments_across", 4, 2, 64);
    return s;
  }
  // Unreachable: Choice() accepted only known names.
  m.source().Fail(m.Path("type"), "unhandled shape type '" + type + "'");
}

}  // namespace

const std::vector<std::string>& ShapeTypeNames() {
  static const std::vector<std::string> names = {
      "plane", "sphere", "box", "capsule", "cylinder", "mesh", "icosphere", "torus",
      "u_slot", "thin_plate", "cup", "block_with_hole", "l_rod", "spoon"};
  return names;
}

ShapeConfig ReadShapeConfig(const YamlMap& shape, const std::string& config_dir) {
  ShapeConfig config;
  config.key = shape.path();
  const std::string type = shape.Choice("type", ShapeTypeNames());
  config.shape = ReadVariant(shape, type, config_dir);
  shape.WarnUnknownKeys();
  return config;
}

bool IsPlane(const ShapeConfig& shape) { return std::holds_alternative<PlaneShape>(shape.shape); }

}  // namespace haptics
