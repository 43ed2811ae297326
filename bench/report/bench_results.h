#pragma once
// Everything one benchmark run measured, as plain data for the report and CSV
// writers. NaN marks a value that was not measured for a case.
#include <limits>
#include <string>
#include <vector>

#include "bench/cases/bench_models.h"
#include "bench/cases/haptic_paths.h"
#include "bench/common/machine_info.h"
#include "bench/cases/scenarios.h"
#include "pd_core/geometry/pose.h"
#include "pd_core/polydepth/penetration_result.h"

namespace pd_bench {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kPocketProbe = 1e-3;  // see PdOutcome::in_pocket
// bench_pd's seed unless --seed says otherwise (haptic_work uses it too: the same paths).
inline constexpr uint64_t kDefaultBenchSeed = 20240611;

// One PolyDepth answer plus its independent checks.
struct PdOutcome {
  bool in_collision = false;  // solver's own collision verdict
  bool valid = false;         // result.valid
  bool verified_free = false; // pd::InCollision at the returned translation is false
  // Free at the answer but colliding again kPocketProbe * depth further out
  // along the same direction: a thin pocket of free space, not an escape.
  bool in_pocket = false;
  double depth = kNaN;        // m
  double time_us = kNaN;      // result.time_us
  int iterations = 0, contacts = 0;
  int starts = 0;             // result.starts (cold starts out-projected)
  int iterated_starts = 0;    // result.iterated_starts (searches of the contact space)
  double box_tests = 0, triangle_tests = 0;  // result.box_tests / triangle_tests (work)
  pd::PenetrationResult::Work work;          // result.work: that work by kind of query
  // Still free kHapticFreeMargin (2e-6) of the pair's size further along the
  // answer: verified free, not resting on a touching contact.
  bool free_beyond = false;
  std::string initializer;
  pd::Vector3 translation_W = pd::Vector3::Zero();
};

struct RefOutcome {
  double depth = kNaN;     // reference PD (m)
  double time_ms = kNaN;   // wall time of ReferencePenetrationDepth
  int directions = 0;      // directional exits it evaluated
  // ReferenceInCollision at PolyDepth's translation: an independent check
  // that shares no code with the solver.
  bool pd_answer_free = false;
  // pd::InCollision at the reference's own translation (plus 1e-6 of the
  // pair size): the reference's answer is a real escape, so a PolyDepth
  // answer above it is a real loss.
  bool ref_answer_free = false;
};

struct FclOutcome {
  double convex_depth = kNaN, convex_time_us = kNaN;
  bool convex_collide = false;
  double mesh_depth = kNaN, mesh_time_us = kNaN;
  int mesh_contacts = 0;
  bool mesh_collide = false;
};

struct CaseRecord {
  Case c;
  PdOutcome pd;
  bool has_ref = false;
  RefOutcome ref;
  // The reference again at the run's heavier check settings (a sample of
  // the random scenario's reference cases): how far the reference itself is
  // from converged.
  bool has_ref_check = false;
  RefOutcome ref_check;
  bool has_fcl = false;
  FclOutcome fcl;
};

struct ScenarioResult {
  Scenario scenario;
  std::string description;
  int steps_total = 0;            // cases generated (paths include free steps)
  std::vector<CaseRecord> cases;  // all generated cases, in order
};

// One knob configuration on one pair and scenario.
struct SweepRow {
  std::string pair, config;
  std::string knob, value;   // config split at '='; both empty for the defaults
  Scenario scenario;
  int n = 0;                 // colliding cases solved
  double median_us = kNaN, p90_us = kNaN;
  double mean_iterations = kNaN;
  double valid_rate = kNaN;  // result.valid && verified free
  int n_ref = 0;
  double mean_abs_error = kNaN, signed_mean_error = kNaN, p95_abs_error = kNaN;
};

struct PairResult {
  BenchPair pair;
  std::vector<ScenarioResult> scenarios;
  int probe_hull_vertices = 0, scene_hull_vertices = 0;
  bool hulls_consistent = true;
};

struct RunSettings {
  bool quick = false;
  int random_cases = 0, path_steps = 0, shallow_steps = 0;
  double shallow_depth_fraction = 0.0;
  int ref_random = 0, ref_path = 0, ref_shallow = 0;  // reference subset sizes (small pairs)
  int ref_random_large = 0, ref_path_large = 0, ref_shallow_large = 0;  // pairs > large_tris
  int large_tris = 0;
  int ref_directions = 0, ref_refine_iterations = 0, ref_refine_starts = 0;
  int ref_threads = 1;
  // Per small pair, this many of the random scenario's reference cases are
  // solved again by a heavier reference (directions, refinement evaluations
  // and starts below): the reference's own convergence, in the report.
  int ref_check_random = 0;
  int ref_check_directions = 0, ref_check_refine_iterations = 0, ref_check_refine_starts = 0;
  int fcl_cases = 0;        // per scenario, on top of the reference subset
  int sweep_cases = 0;      // per scenario, on top of the reference subset
  int fcl_max_contacts = 0;
  int haptic_steps = 0;     // poses per haptic path (1 ms apart)
  int haptic_ref = 0;       // reference PDs per haptic path
  // The haptic reference's directions and evaluations per refinement start
  // (its own: the haptic pairs' meshes are larger).
  int haptic_ref_directions = 0, haptic_ref_refine_iterations = 0;
  // The haptic paths solved again with PolyDepthOptions::max_time_us at this
  // (us; 0: not run): the geometry thread's bounded-time mode.
  double haptic_budget_us = 0.0;
  // More paths of each haptic pair (other seeds), solved unbounded and
  // bounded with their answers checked free; no FCL or reference: the max
  // of one path depends on that path.
  int haptic_more_paths = 0;
  uint64_t seed = 0;        // bench_pd's default: kDefaultBenchSeed
  std::string mesh_dir, out_dir;
  // Scenarios to run (random, path, shallow); empty = all.
  std::vector<std::string> scenarios;
  bool Runs(Scenario s) const;
};

// A warm answer counts as free only if the tool stays free this much further
// along the answer (fraction of the pair's size): no thin free pockets.
inline constexpr double kHapticFreeMargin = 2e-6;

struct HapticStep {
  Case c;
  PdOutcome pd;
  bool free_beyond = false;   // still free kHapticFreeMargin * size further out
  double cpu_us = kNaN;         // the query's CPU time (haptic_bench.cc, SolveAlongPath)
  double budget_cpu_us = kNaN;  // the bounded pass's
  bool converged = true;      // result.converged
  bool cold_restart = false;  // colliding, not the first pose, warm start failed
  bool cross_checked = false; // the deep coherent answer was checked against cold starts
  double box_tests = 0, triangle_tests = 0;
  // The answers come from a solver that defers its list rebuilds
  // (PolyDepthOptions::defer_list_builds) to PrepareNext, run after each
  // answer until the next pose is due (the server's geometry thread):
  // what that call did.
  double prepare_us = 0.0;       // its wall time
  double prepare_box_tests = 0;  // its work
  int lists_completed = 0;       // rebuilds it completed (now in use)
  bool prepare_paused = false;   // stopped by the next pose, goes on after it
  // The same pose solved by a second warm-started solver that rebuilds its
  // lists inside the query (defer_list_builds off): the comparison.
  double inquery_time_us = kNaN;
  bool inquery_in_collision = false;
  int list_builds = 0;         // its result.list_builds: leaf-pair list rebuilds
  double list_build_us = 0.0;  // their wall time, part of inquery_time_us
  double fcl_time_us = kNaN;
  bool fcl_collide = false;
  bool has_ref = false;
  RefOutcome ref;
  // The reference again at the run's heavier check settings (a sample of
  // the random scenario's reference cases): how far the reference itself is
  // from converged.
  bool has_ref_check = false;
  RefOutcome ref_check;
  // The same pose solved by a second warm-started solver with the time
  // budget (RunSettings::haptic_budget_us); has_budget false when not run.
  bool has_budget = false;
  bool budget_in_collision = false, budget_converged = true;
  bool budget_free = false;  // valid, verified free and free kHapticFreeMargin further out
  double budget_depth = kNaN, budget_time_us = kNaN;
  pd::Vector3 budget_translation_W = pd::Vector3::Zero();
};

// One more path of a haptic pair (RunSettings::haptic_more_paths): the
// colliding poses' times and work, unbounded and bounded, as the first path
// is solved; answers checked free (+kHapticFreeMargin).
struct HapticPathRun {
  uint64_t path_seed = 0;
  std::vector<double> us, work, depth;  // colliding poses, unbounded
  std::vector<double> cpu_us, budget_cpu_us;  // their CPU time, unbounded and bounded
  int cold_restarts = 0, not_free = 0;
  std::vector<double> budget_us;         // colliding poses, bounded
  int budget_stopped = 0, budget_not_free = 0;
};

struct HapticPairResult {
  HapticPairSpec spec;
  BenchPair pair;
  std::string description;
  uint64_t path_seed = 0;
  std::vector<HapticStep> steps;
  std::vector<HapticPathRun> more_paths;
};

struct BenchRun {
  MachineInfo machine;
  RunSettings settings;
  std::vector<std::shared_ptr<const ModelInfo>> models;  // precomputation table
  std::vector<std::string> skipped;                      // pairs skipped, with reasons
  std::vector<PairResult> pairs;
  std::vector<SweepRow> sweep;
  std::vector<HapticPairResult> haptic;  // the haptic scenario (haptic_bench.h)
  double total_seconds = 0.0;
  std::string load_average_end;
};

}  // namespace pd_bench
