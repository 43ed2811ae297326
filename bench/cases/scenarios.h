#pragma once
// Probe configurations for the three benchmark scenarios. The scene sits at
// X_WS (bounding-box centre at the world origin, no rotation); every case is a
// probe pose X_WP. Lengths in metres.
#include <cstdint>
#include <string>
#include <vector>

#include "bench/cases/bench_models.h"
#include "pd_core/geometry/pose.h"

namespace pd_bench {

enum class Scenario { kRandom, kPath, kShallow };
const char* ScenarioName(Scenario s);

struct Case {
  int index = 0;        // position in the scenario (step number on a path)
  pd::Isometry3 X_WP = pd::Isometry3::Identity();
  bool colliding = false;  // pd::InCollision at the query pose
};

struct ScenarioCases {
  Scenario scenario;
  std::string description;  // how the cases were made, for the report
  std::vector<Case> cases;
};

// Scene pose used by all scenarios: bounding-box centre at the origin.
pd::Isometry3 ScenePose(const BenchPair& pair);

// (a) Random orientation, probe centre at a uniformly random direction and
// distance in [0.1, 0.8] * scene radius from the scene centre; only colliding
// configurations are kept (up to `count`).
ScenarioCases RandomCases(const BenchPair& pair, int count, uint64_t seed);

// (b) `steps` poses along a straight line through the scene (passing 0.2
// scene radii from its centre, from -1.2 to +1.2 radii) with a slow 90 degree
// rotation spread over the path. Non-colliding steps are kept (a real motion).
ScenarioCases PathCases(const BenchPair& pair, int steps, uint64_t seed);

// (c) Haptic-like sliding: the probe centre travels half a great circle around
// the scene centre with a slow 45 degree rotation; at each step the probe is
// placed just touching the scene from outside along the radial direction and
// then pushed in radially by depth_fraction * (probe radius + scene radius).
ScenarioCases ShallowCases(const BenchPair& pair, int steps, double depth_fraction,
                           uint64_t seed);

}  // namespace pd_bench
