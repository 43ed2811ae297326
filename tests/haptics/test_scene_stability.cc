// Tool + coupling + contact at 1 kHz with the shipped scenes and gains: the
// handle moves into a stiff contact and holds still for 10 s of simulated
// time. With the handle fixed the system is passive, so its energy must not
// grow (the peak energy of the last second is at most that of the second
// second), and it must come to rest: over the last second the tool moves
// less than a micrometre and 1e-5 rad, and the rendered force and torque
// vary by less than 0.1 mN and 1e-5 N·m. Also prints the per-tick renderer
// time (information only: speed is a benchmark's job).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <string>
#include <vector>

#include "haptics/scene/build_scene.h"
#include "haptics/haptic_renderer.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics/tool/rotation_vector.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

constexpr double kHoldSeconds = 10.0;

struct Scenario {
  std::string name;
  std::string config;      // file in config/
  Vector3 start, end;      // handle positions (m)
  Quaternion q_WD;         // handle orientation throughout
  double speed = 0.05;     // m/s from start to end
};

struct Result {
  double energy_max_early = 0.0;    // peak energy from 1 s to 2 s into the hold (J)
  double energy_max_last = 0.0;     // peak energy over the last second (J)
  double tool_p2p_last_s = 0.0;     // peak-to-peak tool position, last second (m)
  double tool_rot_p2p_last_s = 0.0; // peak-to-peak tool rotation vector, last second (rad)
  double force_p2p_last_s = 0.0;    // peak-to-peak output force, last second (N)
  double torque_p2p_last_s = 0.0;   // peak-to-peak output torque, last second (N·m)
  Vector3 final_force = Vector3::Zero();
  double final_depth = 0.0;
  int64_t pd_invalid_ticks_hold = 0;
  int64_t nonfinite = 0;
  std::vector<double> tick_us;      // renderer wall time per tick
  std::vector<double> tick_cpu_us;  // renderer thread CPU time per tick
};

// This thread's CPU time (us): unlike wall time, not inflated by preemption
// on a busy machine.
double ThreadCpuMicros() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e6 * static_cast<double>(ts.tv_sec) + 1e-3 * static_cast<double>(ts.tv_nsec);
}

struct Percentiles {
  double mean = 0, p50 = 0, p99 = 0, max = 0;
};
Percentiles Summarize(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  Percentiles p;
  for (double v : x) p.mean += v / x.size();
  p.p50 = x[x.size() / 2];
  p.p99 = x[x.size() * 99 / 100];
  p.max = x.back();
  return p;
}

double Energy(const HapticRenderer& r, const SceneConfig& config) {
  const double d = r.contact().max_depth;
  return r.tool_dynamics().KineticEnergy() + r.coupling().PotentialEnergy(r.device(), r.tool()) +
         0.5 * config.contact.stiffness * d * d;
}

Result RunScenario(const Scenario& s) {
  const SceneConfig config = LoadSceneConfig(test::ConfigDir() + "/" + s.config);
  const SceneModels models = BuildSceneModels(config);
  HapticRenderer renderer(config, models);
  const double dt = 1.0 / config.servo.rate_hz;
  const int approach = static_cast<int>(std::ceil((s.end - s.start).norm() / (s.speed * dt)));
  const int hold = static_cast<int>(kHoldSeconds / dt);
  const int last_second = static_cast<int>(1.0 / dt);
  Result result;
  Vector3 p_min = Vector3::Constant(1e9), p_max = -p_min, f_min = p_min, f_max = p_max;
  Vector3 rot_min = p_min, rot_max = p_max, tau_min = p_min, tau_max = p_max;
  int64_t invalid_before_hold = 0;
  double t = 0.0;
  for (int i = 0; i <= approach + hold; ++i, t += dt) {
    const double a = std::min(1.0, static_cast<double>(i) / approach);
    const PoseSample pose = test::MakePose(i, s.start + a * (s.end - s.start), s.q_WD);
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = ThreadCpuMicros();
    const WrenchOutput& out = renderer.Tick(t, &pose);
    result.tick_cpu_us.push_back(ThreadCpuMicros() - cpu0);
    result.tick_us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    result.nonfinite += !out.wrench.AllFinite();
    if (i == approach) invalid_before_hold = renderer.counts().pd_invalid_ticks;
    const int into_hold = i - approach;
    const double e = Energy(renderer, config);
    if (into_hold >= last_second && into_hold < 2 * last_second)
      result.energy_max_early = std::max(result.energy_max_early, e);
    if (into_hold >= hold - last_second) {
      result.energy_max_last = std::max(result.energy_max_last, e);
      const Vector3 p = renderer.tool().X_W.translation();
      const Vector3 rot = RotationVectorFromQuaternion(Quaternion(renderer.tool().X_W.linear()));
      p_min = p_min.cwiseMin(p), p_max = p_max.cwiseMax(p);
      rot_min = rot_min.cwiseMin(rot), rot_max = rot_max.cwiseMax(rot);
      f_min = f_min.cwiseMin(out.wrench.f_W), f_max = f_max.cwiseMax(out.wrench.f_W);
      tau_min = tau_min.cwiseMin(out.wrench.tau_W), tau_max = tau_max.cwiseMax(out.wrench.tau_W);
    }
    result.final_force = out.wrench.f_W;
    result.final_depth = out.penetration_depth;
  }
  result.tool_p2p_last_s = (p_max - p_min).maxCoeff();
  result.force_p2p_last_s = (f_max - f_min).maxCoeff();
  result.torque_p2p_last_s = (tau_max - tau_min).maxCoeff();
  result.tool_rot_p2p_last_s = (rot_max - rot_min).maxCoeff();
  result.pd_invalid_ticks_hold = renderer.counts().pd_invalid_ticks - invalid_before_hold;

  const Percentiles wall = Summarize(result.tick_us), cpu = Summarize(result.tick_cpu_us);
  std::printf("[ timing   ] %-22s renderer per tick (us): wall mean %.1f p50 %.1f p99 %.1f max %.1f | "
              "thread CPU mean %.1f p50 %.1f p99 %.1f max %.1f (%zu ticks)\n",
              s.name.c_str(), wall.mean, wall.p50, wall.p99, wall.max, cpu.mean, cpu.p50, cpu.p99,
              cpu.max, result.tick_us.size());
  std::printf("[ result   ] %-22s final |f| %.3f N, depth %.2f mm; last second p2p: tool %.1e m, "
              "%.1e rad, force %.1e N, torque %.1e N·m\n",
              s.name.c_str(), result.final_force.norm(), 1e3 * result.final_depth,
              result.tool_p2p_last_s, result.tool_rot_p2p_last_s, result.force_p2p_last_s,
              result.torque_p2p_last_s);
  return result;
}

void ExpectStableContact(const Result& r) {
  EXPECT_EQ(r.nonfinite, 0);
  EXPECT_GT(r.final_depth, 0.0) << "the scenario must end in contact";
  // Passive: no energy growth while held (a sliver for round-off).
  EXPECT_GT(r.energy_max_early, 0.0);
  EXPECT_LE(r.energy_max_last, r.energy_max_early * (1.0 + 1e-6) + 1e-12);
  // At rest.
  EXPECT_LT(r.tool_p2p_last_s, 1e-6);
  EXPECT_LT(r.tool_rot_p2p_last_s, 1e-5);
  EXPECT_LT(r.force_p2p_last_s, 1e-4);
  EXPECT_LT(r.torque_p2p_last_s, 1e-5);
  EXPECT_EQ(r.pd_invalid_ticks_hold, 0);
}

const Quaternion kSpoonDown(std::sqrt(0.5), 0, std::sqrt(0.5), 0);  // tool x -> world -z

TEST(SceneStability, BoxOnBoxHeldPress) {
  // Handle sinks to where the box bottom would be 1 cm into the table:
  // series spring 1000 * 3000 / 4000 N/m -> 7.5 N up, tool 2.5 mm deep.
  const Result r = RunScenario({"box_on_box", "box_on_box.yaml", Vector3(0.005, -0.003, 0.03),
                        Vector3(0.005, -0.003, 0.0), Quaternion::Identity()});
  ExpectStableContact(r);
  EXPECT_NEAR(r.final_force.z(), 7.5, 0.01);
  EXPECT_NEAR(r.final_depth, 0.0025, 1e-5);
}

TEST(SceneStability, BoxOnBoxTiltedPressOnAnEdge) {
  const Result r = RunScenario({"box_on_box_tilted", "box_on_box.yaml", Vector3(0.0, 0.0, 0.03),
                        Vector3(0.0, 0.0, 0.004),
                        Quaternion(Eigen::AngleAxisd(0.3, Vector3::UnitX()))});
  ExpectStableContact(r);
  EXPECT_GT(r.final_force.z(), 1.0);
}

TEST(SceneStability, SpoonPressedOnTheCupFloor) {
  // Tip 4 mm past the floor (floor top z = -0.055, tip 8.94 cm below the grip).
  const Result r = RunScenario({"spoon_in_cup_floor", "spoon_in_cup.yaml", Vector3(0.0, 0.0, 0.05),
                        Vector3(0.0, 0.0, 0.0304), kSpoonDown});
  ExpectStableContact(r);
  EXPECT_GT(r.final_force.z(), 1.0);
}

TEST(SceneStability, SpoonPressedAgainstTheCupWall) {
  // Bowl 4 cm deep in the cup, pushed sideways into the wall.
  const Result r = RunScenario({"spoon_in_cup_wall", "spoon_in_cup.yaml", Vector3(0.0, 0.0, 0.045),
                        Vector3(0.0, 0.024, 0.045), kSpoonDown, 0.02});
  ExpectStableContact(r);
  EXPECT_LT(r.final_force.y(), -0.5);
}

TEST(SceneStability, PegPressedOnTheBlockTop) {
  // The 4 cm peg touches the top face (z = 0) with its grip at z = 0.04.
  const Result r = RunScenario({"peg_on_block_top", "peg_in_hole.yaml", Vector3(0.025, 0.0, 0.065),
                        Vector3(0.025, 0.0, 0.036), Quaternion::Identity()});
  ExpectStableContact(r);
  EXPECT_NEAR(r.final_force.z(), 3.0, 0.05);  // 4 mm at 750 N/m
}

TEST(SceneStability, PegPressedAgainstTheHoleWall) {
  // Peg 2 cm into the hole, pushed 3 mm sideways (about 1 mm clearance).
  const Result r = RunScenario({"peg_against_hole_wall", "peg_in_hole.yaml", Vector3(0.0, 0.0, 0.02),
                        Vector3(0.003, 0.0, 0.02), Quaternion::Identity(), 0.02});
  ExpectStableContact(r);
  EXPECT_LT(r.final_force.x(), -0.5);
}

}  // namespace
}  // namespace haptics
