#include "haptics/scene/load_scene_config.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>

#include "haptics/scene/shape_config_reader.h"
#include "haptics/scene/yaml_reader.h"
#include "msgs/sender_identity.h"

namespace haptics {
namespace {

// LCM refuses longer channel names (LCM_MAX_CHANNEL_NAME_LENGTH).
constexpr size_t kMaxChannelLength = 63;
// How far a configured quaternion may be from unit length before we refuse to
// guess what was meant (the same tolerance as incoming probe poses).
constexpr double kQuaternionTolerance = 1e-3;

std::string DirectoryOf(const std::string& file) {
  const std::filesystem::path dir = std::filesystem::path(file).parent_path();
  return dir.empty() ? "." : dir.string();
}

// {position: [x, y, z] m, orientation: [w, x, y, z]}, both optional.
Isometry3 ReadPose(const YamlMap& m) {
  const Vector3 p = m.VectorOr("position", Vector3::Zero(), Range::Closed(-100.0, 100.0, "m"));
  Quaternion q = Quaternion::Identity();
  if (m.Has("orientation")) {
    const YAML::Node n = m.Get("orientation", "");
    const std::string key = m.Path("orientation");
    const std::string expected = "must be a unit quaternion [w, x, y, z] (norm within 1e-3 of 1)";
    if (!n.IsSequence() || n.size() != 4) m.source().Fail(key, expected + ", got " + DescribeNode(n));
    double c[4];
    for (int i = 0; i < 4; ++i)
      c[i] = ReadNumber(n[i], key + "[" + std::to_string(i) + "]", Range::Closed(-1.001, 1.001, ""),
                        m.source());
    q = Quaternion(c[0], c[1], c[2], c[3]);
    if (std::abs(q.norm() - 1.0) > kQuaternionTolerance)
      m.source().Fail(key, expected + ", got norm " + std::to_string(q.norm()));
    q.normalize();
  }
  m.WarnUnknownKeys();
  Isometry3 X = Isometry3::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = p;
  return X;
}

Isometry3 ReadPoseOr(const YamlMap& parent, const std::string& key) {
  return parent.Has(key) ? ReadPose(parent.Map(key)) : Isometry3::Identity();
}

// [Ixx, Iyy, Izz] or a symmetric 3x3 [[..], [..], [..]], kg·m² in T. Must be a
// physical inertia: positive definite, principal moments obeying the triangle
// inequality.
Matrix3 ReadInertia(const YamlMap& tool) {
  const std::string key = tool.Path("inertia");
  const YamlSource& src = tool.source();
  const Range diagonal = Range::Positive(1.0, "kg·m²");
  const Range off_diagonal = Range::Closed(-1.0, 1.0, "kg·m²");
  const YAML::Node n = tool.Get("inertia", "[Ixx, Iyy, Izz] or a 3x3 list of lists, kg·m²");
  const std::string expected = "must be [Ixx, Iyy, Izz] with each in " + diagonal.Describe() +
                               ", or a symmetric 3x3 list of lists";
  if (!n.IsSequence() || n.size() != 3) src.Fail(key, expected + ", got " + DescribeNode(n));
  Matrix3 I = Matrix3::Zero();
  if (n[0].IsScalar()) {
    I.diagonal() = ReadVector3(n, key, diagonal, src);
  } else {
    for (int r = 0; r < 3; ++r) {
      const std::string row_key = key + "[" + std::to_string(r) + "]";
      if (!n[r].IsSequence() || n[r].size() != 3)
        src.Fail(row_key, expected + ", got " + DescribeNode(n[r]));
      for (int c = 0; c < 3; ++c)
        I(r, c) = ReadNumber(n[r][c], row_key + "[" + std::to_string(c) + "]",
                             r == c ? diagonal : off_diagonal, src);
    }
    if (!I.isApprox(I.transpose(), 1e-9)) src.Fail(key, "must be symmetric");
  }
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Matrix3>(I).eigenvalues();
  if (moments.minCoeff() <= 0.0) src.Fail(key, "must be positive definite");
  const double slack = 1e-9 * moments.sum();
  for (int i = 0; i < 3; ++i) {
    if (moments[i] > moments[(i + 1) % 3] + moments[(i + 2) % 3] + slack)
      src.Fail(key, "principal moments must obey the triangle inequality (I1 <= I2 + I3), "
                    "which every rigid body does");
  }
  return I;
}

ToolConfig ReadTool(const YamlMap& m, const std::string& dir) {
  ToolConfig tool;
  tool.shape = ReadShapeConfig(m.Map("shape"), dir);
  if (IsPlane(tool.shape))
    m.source().Fail(m.Path("shape.type"), "'plane' is unbounded and cannot be the tool; use a "
                                          "bounded shape (box, sphere, capsule, cylinder, mesh, ...)");
  tool.X_TG = ReadPoseOr(m, "geometry_pose");
  tool.mass = m.Number("mass", Range::Positive(10.0, "kg"));
  tool.I_T = ReadInertia(m);
  tool.gravity_W = m.VectorOr("gravity", Vector3::Zero(), Range::Closed(-20.0, 20.0, "m/s²"));
  m.WarnUnknownKeys();
  return tool;
}

std::vector<ObjectConfig> ReadObjects(const YamlMap& root, const std::string& dir) {
  const YAML::Node list = root.Get("objects", "a list of scene objects");
  const YamlSource& src = root.source();
  if (!list.IsSequence()) src.Fail("objects", "must be a list of objects, got " + DescribeNode(list));
  if (list.size() == 0) src.Warn("objects", "empty: nothing to touch");
  std::vector<ObjectConfig> objects;
  for (size_t i = 0; i < list.size(); ++i) {
    const YamlMap m(list[i], "objects[" + std::to_string(i) + "]", &src);
    ObjectConfig object;
    object.name = m.StringOr("name", "object_" + std::to_string(i));
    object.shape = ReadShapeConfig(m.Map("shape"), dir);
    object.X_WS = ReadPoseOr(m, "pose");
    m.WarnUnknownKeys();
    objects.push_back(std::move(object));
  }
  return objects;
}

ContactConfig ReadContact(const YamlMap& m) {
  ContactConfig c;
  c.stiffness = m.Number("stiffness", Range::Positive(1e5, "N/m"));
  c.damping = m.Number("damping", Range::NonNegative(1e3, "N·s/m"));
  c.torque_scale = m.NumberOr("torque_scale", 1.0, Range::NonNegative(10.0, ""));
  c.cull_margin = m.NumberOr("cull_margin", 0.005, Range::NonNegative(1.0, "m"));
  if (m.Has("torque_model")) {
    c.torque_model = m.Choice("torque_model", {"pressure_centre", "region_points"}) == "region_points"
                         ? TorqueModel::kRegionPoints
                         : TorqueModel::kPressureCentre;
  }
  if (m.Has("geometry_thread")) {
    const std::string mode = m.Choice("geometry_thread", {"auto", "on", "off"});
    c.geometry_thread = mode == "on"    ? GeometryThreadMode::kOn
                        : mode == "off" ? GeometryThreadMode::kOff
                                        : GeometryThreadMode::kAuto;
  }
  c.sync_budget = m.NumberOr("sync_budget", 0.25, Range::Positive(1.0, "of the servo period"));
  c.geometry_cpu = m.IntegerOr("geometry_cpu", -1, -1, 1023);
  c.geometry_budget_s =
      1e-3 * m.NumberOr("geometry_budget_ms", 0.9, Range::Closed(0.05, 1000.0, "ms"));
  c.invalid_hold_s = 1e-3 * m.NumberOr("invalid_hold_ms", 200.0, Range::Closed(1.0, 5000.0, "ms"));
  c.model_max_age_s = 1e-3 * m.NumberOr("model_max_age_ms", 250.0, Range::Closed(1.0, 5000.0, "ms"));
  c.model_age_ramp_s = 1e-3 * m.NumberOr("model_age_ramp_ms", 250.0, Range::Closed(1.0, 5000.0, "ms"));
  m.WarnUnknownKeys();
  return c;
}

CouplingConfig ReadCoupling(const YamlMap& m, const DeviceConfig& device) {
  CouplingConfig c;
  const YamlMap t = m.Map("translational");
  // The device must be able to render the coupling spring stably.
  const Range k_t(Range::Positive(device.max_stiffness, "N/m (max_stiffness of device " + device.file + ")"));
  c.k_translational = t.Number("stiffness", k_t);
  c.b_translational = t.Number("damping", Range::NonNegative(1e3, "N·s/m"));
  t.WarnUnknownKeys();
  const YamlMap r = m.Map("rotational");
  c.k_rotational = r.Number("stiffness", Range::Positive(100.0, "N·m/rad"));
  c.b_rotational = r.Number("damping", Range::NonNegative(10.0, "N·m·s/rad"));
  r.WarnUnknownKeys();
  c.velocity_filter_hz = m.NumberOr("velocity_filter_hz", 100.0, Range::Positive(5000.0, "Hz"));
  m.WarnUnknownKeys();
  return c;
}

ServoConfig ReadServo(const YamlMap& m) {
  ServoConfig s;
  s.rate_hz = m.Number("rate_hz", Range::Closed(100.0, 10000.0, "Hz"));
  // At least two periods, or ordinary jitter would trip it.
  const double min_ms = 2000.0 / s.rate_hz;
  s.watchdog_timeout_s =
      1e-3 * m.NumberOr("watchdog_timeout_ms", 50.0, Range::Closed(min_ms, 1000.0, "ms"));
  s.watchdog_ramp_s = m.NumberOr("watchdog_ramp_s", 0.05, Range::Closed(1e-3, 1.0, "s"));
  s.soft_engage_s = m.NumberOr("soft_engage_s", 1.0, Range::NonNegative(10.0, "s"));
  s.cpu = m.IntegerOr("cpu", -1, -1, 1023);
  s.realtime_priority = m.IntegerOr("realtime_priority", 80, 0, 99);
  s.status_rate_hz = m.NumberOr("status_rate_hz", 10.0, Range::Closed(0.1, 100.0, "Hz"));
  if (m.Has("phase_lock")) s.phase_lock = m.Choice("phase_lock", {"true", "false"}) == "true";
  // Below half a period, so a pose arriving on time never waits a whole one.
  s.phase_lock_target_us = m.NumberOr("phase_lock_target_us", 150.0,
                                      Range::Closed(0.0, 0.5e6 / s.rate_hz, "us"));
  if (m.Has("tick_trigger"))
    s.pose_triggered = m.Choice("tick_trigger", {"pose", "fixed_rate"}) == "pose";
  s.pose_window_us = m.NumberOr("pose_window_us", 400.0, Range::Closed(0.0, 0.5e6 / s.rate_hz, "us"));
  if (m.Has("io_on_servo_cpu")) s.io_on_servo_cpu = m.Choice("io_on_servo_cpu", {"true", "false"}) == "true";
  m.WarnUnknownKeys();
  return s;
}

LcmConfig ReadLcm(const YamlMap& m) {
  LcmConfig l;
  l.url = m.StringOr("url", l.url);
  const char* keys[] = {"pose_channel", "wrench_channel", "status_channel"};
  std::string* values[] = {&l.pose_channel, &l.wrench_channel, &l.status_channel};
  for (int i = 0; i < 3; ++i) {
    *values[i] = m.StringOr(keys[i], *values[i]);
    if (values[i]->size() > kMaxChannelLength)
      m.source().Fail(m.Path(keys[i]), "must be at most 63 characters (LCM's limit)");
    for (int j = 0; j < i; ++j) {
      if (*values[i] == *values[j])
        m.source().Fail(m.Path(keys[i]), "must differ from " + m.Path(keys[j]) + " ('" +
                                             *values[j] + "')");
    }
  }
  if (m.Has("accept_session") && !haptics_msgs::ParseSession(m.String("accept_session"), &l.accept_session))
    m.source().Fail(m.Path("accept_session"),
                    "must be a non-zero 64-bit session id, 0x-prefixed hex or decimal; got '" +
                        m.String("accept_session") + "'");
  l.accept_device = m.StringOr("accept_device", "");
  if (l.accept_device.size() > haptics_msgs::kMaxDeviceNameBytes)
    m.source().Fail(m.Path("accept_device"), "must be at most 64 bytes (probe_pose_t.sender_device)");
  m.WarnUnknownKeys();
  return l;
}

}  // namespace

DeviceConfig LoadDeviceConfig(const std::string& path, std::vector<std::string>* warnings) {
  const YamlSource src{path, warnings};
  const YamlMap m(LoadYamlFile(path), "", &src);
  DeviceConfig d;
  d.file = path;
  d.name = m.StringOr("name", std::filesystem::path(path).stem().string());
  d.max_force = m.Number("max_force", Range::Positive(100.0, "N"));
  d.max_torque = m.Number("max_torque", Range::Positive(10.0, "N·m"));
  d.max_force_rate = m.Number("max_force_rate", Range::Positive(1e6, "N/s"));
  // Default: the same time to full scale as the force.
  d.max_torque_rate = m.NumberOr("max_torque_rate", d.max_force_rate * d.max_torque / d.max_force,
                                 Range::Positive(1e5, "N·m/s"));
  d.max_stiffness = m.Number("max_stiffness", Range::Positive(1e6, "N/m"));
  const YamlMap ws = m.Map("workspace");
  const Range coordinate = Range::Closed(-10.0, 10.0, "m");
  d.workspace_min = ws.Vector("min", coordinate);
  d.workspace_max = ws.Vector("max", coordinate);
  for (int i = 0; i < 3; ++i) {
    if (!(d.workspace_min[i] < d.workspace_max[i]))
      src.Fail("workspace.max[" + std::to_string(i) + "]",
               "must be greater than workspace.min[" + std::to_string(i) + "]");
  }
  ws.WarnUnknownKeys();
  m.WarnUnknownKeys();
  return d;
}

SceneConfig LoadSceneConfig(const std::string& path) {
  SceneConfig config;
  config.file = path;
  const YamlSource src{path, &config.warnings};
  const YamlMap root(LoadYamlFile(path), "", &src);
  const std::string dir = DirectoryOf(path);

  config.name = root.StringOr("name", std::filesystem::path(path).stem().string());
  // The device first: it bounds the coupling gains.
  std::filesystem::path device_path(root.String("device"));
  if (device_path.is_relative()) device_path = std::filesystem::path(dir) / device_path;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(device_path, ec))
    src.Fail("device", "device profile '" + device_path.lexically_normal().string() +
                           "' does not exist (relative paths are resolved against the config "
                           "file's directory)");
  config.device = LoadDeviceConfig(device_path.lexically_normal().string(), &config.warnings);

  config.tool = ReadTool(root.Map("tool"), dir);
  config.objects = ReadObjects(root, dir);
  config.contact = ReadContact(root.Map("contact"));
  config.coupling = ReadCoupling(root.Map("coupling"), config.device);
  config.servo = ReadServo(root.Map("servo"));
  if (root.Has("lcm")) config.lcm = ReadLcm(root.Map("lcm"));
  if (root.Has("cache_dir")) {
    std::filesystem::path cache(root.String("cache_dir"));
    if (cache.is_relative()) cache = std::filesystem::path(dir) / cache;
    config.cache_dir = cache.lexically_normal().string();
  }
  if (root.Has("description")) root.Get("description", "");  // free text
  root.WarnUnknownKeys();
  return config;
}

}  // namespace haptics
