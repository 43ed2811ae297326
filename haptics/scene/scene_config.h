#pragma once
// A haptic scene as configured in YAML (config/*.yaml, read by
// load_scene_config.h): the tool, the scene objects, contact and coupling
// gains, the device profile, servo-loop timing and the LCM transport. Plain
// data, validated by the reader. SI units: m, kg, s, N, N·m, rad; poses are
// position [x, y, z] and quaternion [w, x, y, z].
#include <string>
#include <variant>
#include <vector>

#include "haptics/tool/spatial.h"
#include "pd_core/geometry/make_shapes.h"

namespace haptics {

// Geometry sources. Sizes in metres. Primitives (plane, sphere, box, capsule,
// cylinder) are exact shapes (pd::Geometry); the rest are triangle meshes:
// loaded from a file or generated (see pd_core/geometry/make_shapes.h for each).
struct MeshFileShape {
  std::string path;    // absolute, resolved against the config file's directory
  double scale = 1.0;  // file units -> m
  bool convex = false;  // declared convex: verified at load, solved by GJK/EPA
  int max_triangles = 5'000'000;  // larger files are refused before loading (pd::MeshLoadOptions)
};
// Half-space z <= 0 of its frame: the object's pose places the plane (z-up,
// through the pose origin). Scene objects only, never the tool.
struct PlaneShape {};
struct SphereShape { double radius; };
struct BoxShape { Vector3 half_extents; };
// Axis z: a segment of `length` between the cap centres, swept by a ball of
// `radius` (overall length + 2 radius).
struct CapsuleShape { double radius, length; };
// Axis z, z in [-length/2, length/2].
struct CylinderShape { double radius, length; };
struct IcosphereShape { double radius; int subdivisions; };
struct TorusShape { double major_radius, minor_radius; int major_segments, minor_segments; };
struct USlotShape { Vector3 half_extents; double slot_width, slot_depth; };
struct ThinPlateShape { double half_x, half_y, half_thickness; };
struct CupShape { double outer_radius, height, wall_thickness, floor_thickness; int segments; };
struct BlockWithHoleShape { Vector3 half_extents; double hole_half_width; bool round; int segments; };
struct LRodShape { double arm_x, arm_y, width, thickness; };
struct SpoonShape { pd::SpoonDimensions dims; };

using ShapeVariant =
    std::variant<MeshFileShape, PlaneShape, SphereShape, BoxShape, CapsuleShape, CylinderShape,
                 IcosphereShape, TorusShape, USlotShape, ThinPlateShape, CupShape,
                 BlockWithHoleShape, LRodShape, SpoonShape>;

struct ShapeConfig {
  std::string key;  // where it was configured, e.g. "objects[1].shape" (for messages)
  ShapeVariant shape;
};

struct ObjectConfig {
  std::string name;
  ShapeConfig shape;
  Isometry3 X_WS = Isometry3::Identity();  // pose of the object's geometry frame S in W
};

// The simulated tool T. Its mass properties are rendering parameters: the
// mass sits at the tool origin (the coupling point) and the inertia is about
// that origin, in T.
struct ToolConfig {
  ShapeConfig shape;
  Isometry3 X_TG = Isometry3::Identity();  // geometry (mesh frame G) in T
  double mass = 0.0;                       // kg
  Matrix3 I_T = Matrix3::Zero();           // kg·m², about the origin of T, in T
  Vector3 gravity_W = Vector3::Zero();     // m/s²; off by default
};

// Where the local PDs' forces act for the contact torque (penalty_wrench.h).
enum class TorqueModel {
  kPressureCentre,  // default: each region at its centre of pressure, k shared
  kRegionPoints,    // each region's point with the full k (the plain formula)
};

// Where the PD queries run (geometry_thread.h, haptic_renderer.h).
enum class GeometryThreadMode {
  kAuto,  // default: in the tick while queries fit sync_budget of the period, else on the thread
  kOn,    // always on the geometry thread; the tick renders the local contact model
  kOff,   // always in the tick (the tick waits for PolyDepth)
};

struct ContactConfig {
  double stiffness = 0.0;     // N/m, penalty per metre of penetration depth
  double damping = 0.0;       // N·s/m, along the contact normal
  double torque_scale = 1.0;  // multiplies the torque of the local PDs
  double cull_margin = 0.005;  // m, added to the broad phase's swept tool box (broad_phase.h)
  TorqueModel torque_model = TorqueModel::kPressureCentre;
  GeometryThreadMode geometry_thread = GeometryThreadMode::kAuto;
  double sync_budget = 0.25;        // auto: fraction of the servo period queries may take in the tick
  int geometry_cpu = -1;            // pin the geometry thread (-1: the other CPU than servo.cpu, if any)
  // Off the tick: PolyDepth's time budget per query (configured in ms). Below
  // the 1 ms pose period by room for the answer's finish (polydepth.h,
  // max_time_us): at 0.9 ms, haptic_work's 30 seeded mesh-tool paths (5
  // pairs x 6 seeds) answered within 0.98 ms, against 1.14 ms unbounded.
  double geometry_budget_s = 0.0009;
  double invalid_hold_s = 0.2;      // hold-last-valid: decay of a held contact (configured in ms)
  double model_max_age_s = 0.25;    // an older contact model ramps out (configured in ms)
  double model_age_ramp_s = 0.25;   // ... to zero over this time (configured in ms)
};

struct CouplingConfig {
  double k_translational = 0.0;  // N/m
  double b_translational = 0.0;  // N·s/m
  double k_rotational = 0.0;     // N·m/rad
  double b_rotational = 0.0;     // N·m·s/rad
  // Cut-off of the low-pass on finite-differenced device velocity, used when
  // poses carry no measured velocity (Hz).
  double velocity_filter_hz = 100.0;
};

// A device profile (config/devices/*.yaml).
struct DeviceConfig {
  std::string file;            // the profile's path
  std::string name;
  double max_force = 0.0;        // N
  double max_torque = 0.0;       // N·m
  double max_force_rate = 0.0;   // N/s
  double max_torque_rate = 0.0;  // N·m/s
  double max_stiffness = 0.0;    // N/m the device renders stably
  Vector3 workspace_min = Vector3::Zero();  // m, in W (device base = world)
  Vector3 workspace_max = Vector3::Zero();
};

struct ServoConfig {
  double rate_hz = 1000.0;
  double watchdog_timeout_s = 0.05;  // configured in ms
  double watchdog_ramp_s = 0.05;     // force scale 1 -> 0 over this time
  double soft_engage_s = 1.0;        // force scale 0 -> 1 over this time
  int cpu = -1;                      // pin the loop thread to this CPU; -1: no pinning
  int realtime_priority = 80;        // SCHED_FIFO priority; 0: do not ask
  double status_rate_hz = 10.0;
  // Tick phase follows pose arrival (haptics/loop/phase_lock.h): the newest pose
  // waits about phase_lock_target_us (us) for the tick instead of 0..1 period.
  bool phase_lock = true;
  double phase_lock_target_us = 150.0;
  // What starts a tick (servo_loop.h, TickTrigger): the pose's arrival
  // (default; within pose_window_us before the deadline) or the fixed-rate
  // deadline only.
  bool pose_triggered = true;
  double pose_window_us = 400.0;
  // LCM's read thread and the pose receive thread run on the servo's CPU
  // (with cpu >= 0): no wake-up across CPUs between a pose and its tick.
  bool io_on_servo_cpu = true;
};

struct LcmConfig {
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  std::string pose_channel = "PROBE_POSE";
  std::string wrench_channel = "HAPTIC_WRENCH";
  std::string status_channel = "HAPTIC_STATUS";
  // Pin of the pose source (pose_source_lock.h): render only poses from this
  // sender session (0: any) and/or device name (empty: any).
  int64_t accept_session = 0;
  std::string accept_device;
};

struct SceneConfig {
  std::string file;  // the scene file as given
  std::string name;
  ToolConfig tool;
  std::vector<ObjectConfig> objects;
  ContactConfig contact;
  CouplingConfig coupling;
  DeviceConfig device;
  ServoConfig servo;
  LcmConfig lcm;
  // Directory of the mesh precomputation cache (pd_core/mesh/model_cache.h),
  // resolved against the config file's directory; "" (default): no cache.
  std::string cache_dir;
  std::vector<std::string> warnings;  // also logged with spdlog
};

}  // namespace haptics
