#pragma once
// Published numbers the report compares against. These are quoted, not
// measured: the paper's timings and the project's performance targets.
namespace pd_bench {

// Je, Tang, Lee, Lee, Kim: "PolyDepth: Real-time Penetration Depth Computation
// using Iterative Contact-Space Projection", ACM TOG 31(1), 2012: average time
// per random-configuration query on their 2012 hardware.
struct PaperTiming {
  const char* model;
  int triangles;
  double ms_per_query;
  double iterations;  // < 0: not quoted here
};
inline constexpr PaperTiming kPaperTimings[] = {
    {"Torus knot", 3000, 5.53, 2.81},
    {"Buddha", 10000, 6.23, -1},
    {"Bunny", 40000, 7.55, -1},
    {"Dragon", 174000, 12.76, -1},
};

// Project targets.
inline constexpr double kTargetColdKnotMedianUs = 500.0;
// Cold queries (random configurations of real-mesh pairs, issue 13): time
// median and p95, error mean (kTargetMeanError), p95 (kTargetP95Error), max.
inline constexpr double kTargetColdMedianUs = 1000.0;
inline constexpr double kTargetColdP95Us = 5000.0;
inline constexpr double kTargetColdMaxError = 0.10;
inline constexpr double kTargetCoherentMedianUs = 20.0;
inline constexpr double kTargetCoherentP99Us = 100.0;
inline constexpr double kTargetMeanError = 0.005;
inline constexpr double kTargetP95Error = 0.02;
inline constexpr double kTargetBytesPerTriangle = 300.0;
inline constexpr double kTargetBuildMsPer100k = 100.0;

}  // namespace pd_bench
