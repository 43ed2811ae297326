#pragma once
// The haptic scenario (haptic_paths.h) on one tool/object pair: PolyDepth
// warm-started pose after pose, FCL's boolean collide of the same meshes at
// the same poses as the cost yardstick, and the reference PD (no hint from
// the solver) on a spread of colliding poses.
#include <string>
#include <vector>

#include "bench/report/bench_results.h"
#include "bench/report/summaries.h"
#include "bench/cases/haptic_paths.h"
#include "bench/common/stats.h"

namespace pd_bench {

// The pose spacing of the haptic paths (us): a geometry thread answering one
// pose per servo tick has the rest of the millisecond for deferred work.
constexpr double kHapticPosePeriodUs = 1000.0;

// The deepest PD (m) of the range issue 10's warm targets are set for
// (0.5-3 mm): a path that digs deeper where the tool sinks into a thin part
// is reported apart as well.
constexpr double kHapticTargetMaxDepth = 3e-3;

struct HapticSummary {
  int steps = 0, colliding = 0;
  Summary pd_us;           // colliding poses
  Summary in_range_us;     // colliding poses with PD <= kHapticTargetMaxDepth
  Summary deeper_us;       // the deeper ones
  Summary pd_free_us;      // free poses (collision test only)
  Summary fcl_us;          // FCL collide on the colliding poses
  double median_ratio = kNaN, p99_ratio = kNaN;  // PolyDepth / FCL, colliding poses
  double p999_us = kNaN;
  double mean_iterations = kNaN, mean_box_tests = kNaN, mean_triangle_tests = kNaN;
  // Answer first, rebuild after (PolyDepthOptions::defer_list_builds), over
  // the colliding poses: the answer plus the PrepareNext after it (the
  // geometry thread's busy time per pose), PrepareNext alone, the rebuilds
  // it completed and the calls the next pose paused.
  Summary busy_us, prepare_us;
  int lists_completed = 0, prepare_paused = 0;
  // The comparison pass, lists rebuilt inside the queries: its times, and
  // where its tail comes from: the queries that rebuilt the leaf-pair list
  // near the contact and those that did not, the rebuilds' share of its
  // time, and how many of its slowest 1% rebuilt.
  Summary inquery_us, with_build_us, without_build_us;
  double build_time_share = kNaN;
  int inquery_slowest_1pct = 0, inquery_slowest_1pct_with_build = 0;
  int slowest_1pct = 0;
  // Where the work (box + triangle tests) went: over all colliding queries
  // and over the slowest 1% of them.
  WorkShares work, slowest_1pct_work;
  int cold_restarts = 0, cross_checks = 0, not_converged = 0, invalid = 0, not_free_beyond = 0;
  int fcl_disagree = 0;    // FCL's verdict differs from the path's
  int n_ref = 0;
  Summary abs_error;       // |depth - ref| / ref
  // The bounded-time pass (RunSettings::haptic_budget_us), colliding poses:
  // time, answers stopped by the budget, answers not free (+margin), and the
  // error on the same reference poses.
  bool has_budget = false;
  Summary budget_us, budget_abs_error;
  int budget_not_converged = 0, budget_not_free = 0;
  double signed_mean_error = kNaN;
};

// Every path of a pair (the first and RunSettings::haptic_more_paths more),
// colliding poses: the max per path and over all, unbounded and bounded.
struct HapticPathsSummary {
  int paths = 0, colliding = 0;
  std::vector<double> max_us;     // per path, the first first
  double max_us_all = kNaN, in_range_max_us = kNaN, worst_p99_us = kNaN, max_work = kNaN;
  int paths_over_target = 0;      // paths whose max exceeds the warm target
  // The same on the queries' CPU time (their wall time less any time the
  // thread was not running: a stall of the machine, not of the solver).
  double cpu_max_us_all = kNaN;
  int cold_restarts = 0, not_free = 0;
  std::vector<double> budget_max_us;  // per path
  double budget_max_us_all = kNaN;
  int budget_stopped = 0, budget_not_free = 0, budget_paths_over_target = 0;
  std::vector<double> budget_cpu_max_us;  // per path, CPU time
  double budget_cpu_max_us_all = kNaN;
  int budget_cpu_paths_over_target = 0;
};

HapticPairResult RunHapticPair(const BenchPair& pair, const HapticPairSpec& spec,
                               const RunSettings& st);
// The first path's colliding poses in the form of the more paths' runs.
HapticPathRun FirstHapticPathRun(const HapticPairResult& r);
HapticPathsSummary SummarizeHapticPaths(const HapticPairResult& r, double target_max_us);
HapticSummary SummarizeHaptic(const HapticPairResult& r);

}  // namespace pd_bench
