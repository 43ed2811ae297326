#pragma once
// The haptic scenario: a mesh tool sliding over a mesh object the way a hand
// on a device moves it, one pose per millisecond. The object sits at the
// world origin (bounding-box centre); the tool's bounding-box centre travels
// around it on a great circle at a set speed while the tool turns at a set
// rate about a fixed axis, and is kept a set depth inside the object's
// surface (measured radially from first contact). The radial motion is rate
// limited, as a hand's is, so where the surface juts out the tool digs in
// deeper for a while and where it falls away the tool loses contact. Where
// the first contact along the ray jumps outward by more than 6 mm in one
// pose, an overhang has come over the tool: the hand follows the surface
// under it (the gap the tool slides in) or, with no gap within 6 mm, turns
// back along the circle; it never climbs through the overhang from below.
// Twice per path the tool lifts off by 1 mm for 25 ms and comes back.
#include <string>
#include <vector>

#include "bench/cases/bench_models.h"
#include "bench/cases/scenarios.h"

namespace pd_bench {

// Tool and object sizes (bounding-sphere radii, m): a 5 cm tool over a 15 cm object.
inline constexpr double kHapticToolRadius = 0.025;
inline constexpr double kHapticObjectRadius = 0.075;
inline constexpr double kHapticDt = 1e-3;  // s between poses

struct HapticPairSpec {
  std::string name;
  std::string tool, object;  // mesh file names (see bench_models.h)
  double speed_m_s = 0.1;    // tool centre speed along the surface
  double turn_deg_s = 20.0;  // tool rotation rate
  double depth_m = 1.5e-3;   // push below first contact
  bool in_quick = false;
};

std::vector<HapticPairSpec> DefaultHapticPairs();

struct HapticPath {
  std::string description;
  std::vector<Case> cases;  // one per millisecond, free ones included
};

// The path seed of a run seeded with `run_seed` (bench_pd's --seed).
inline uint64_t HapticPathSeed(uint64_t run_seed) { return run_seed + 7; }

// `steps` poses (steps * kHapticDt seconds) of the path for `spec`.
HapticPath MakeHapticPath(const BenchPair& pair, const HapticPairSpec& spec, int steps,
                          uint64_t seed);

}  // namespace pd_bench
