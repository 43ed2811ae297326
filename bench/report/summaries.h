#pragma once
// Per pair and scenario statistics over the colliding cases of a run.
#include <vector>

#include "bench/report/bench_results.h"
#include "bench/common/stats.h"

namespace pd_bench {

// Each kind of query's share of the work (box + triangle tests) of a set of
// answers (PenetrationResult::work); NaN for a set without work.
struct WorkShares {
  double collision = kNaN, localisation = kNaN, out_projection = kNaN, list_builds = kNaN,
         other = kNaN;
};
WorkShares SharesOf(const std::vector<pd::PenetrationResult::Work>& works);

struct BaselineSummary {
  int n = 0;                 // cases it ran on (colliding)
  Summary time_us;
  double time_ratio = kNaN;  // median baseline time / median PolyDepth time, same cases
  int n_ref = 0;             // of those, with a reference
  Summary abs_error;         // |depth - ref| / ref
  double signed_mean_error = kNaN;
  int n_no_collision = 0;    // baseline reported no collision for a colliding case
};

struct ScenarioSummary {
  int n = 0;                 // colliding cases
  Summary time_us;
  double mean_iterations = kNaN, mean_contacts = kNaN;
  double mean_starts = kNaN;    // cold starts out-projected per query
  double mean_iterated_starts = kNaN;  // of those (and coherent starts), iterated per query
  // Work per query (deterministic, unlike times): box and triangle-pair tests.
  double mean_box_tests = kNaN, mean_triangle_tests = kNaN;
  WorkShares work;              // where that work went
  int n_not_free_beyond = 0;    // verified free but not kHapticFreeMargin further out
  double valid_rate = kNaN;     // result.valid
  double verified_rate = kNaN;  // pd::InCollision at the answer is false
  int n_invalid = 0;            // !valid or !verified
  int n_pocket = 0;             // answers in a thin free pocket (PdOutcome::in_pocket)
  int n_ref = 0;
  double ref_free_rate = kNaN;  // ReferenceInCollision at the answer is false
  int n_ref_not_free = 0;       // reference answers pd::InCollision finds colliding
  Summary abs_error;
  Interval abs_error_mean_ci;   // 95% bootstrap interval of abs_error.mean
  double signed_mean_error = kNaN;
  int n_below_ref = 0;          // PolyDepth shallower than the reference by > 1e-6
  // (depth - best) / best with best = min(depth, ref): PolyDepth's overshoot
  // beyond the best escape either method found, blind to a weak reference.
  Summary excess;
  // The reference checked by a heavier one (RunSettings::ref_check_random):
  // (ref - check) / check, a lower bound on the reference's own error; the
  // cases where the check came out shorter by more than 0.1%; PolyDepth's
  // |error| on those cases against each.
  int n_ref_check = 0;
  Summary ref_over_check;
  int n_check_below_ref = 0;
  Summary abs_error_on_check_cases, abs_error_vs_check;
  Summary ref_check_time_ms;
  Summary ref_time_ms;
  double ref_time_ratio = kNaN;  // reference / PolyDepth, on the reference cases
  BaselineSummary fcl_convex, fcl_mesh;
};

// Relative error (depth - ref) / ref; NaN without a positive reference.
double RelativeError(double depth, double ref);

ScenarioSummary Summarize(const ScenarioResult& s);

// Time/error/validity of alternative outcomes for the same cases (knob sweep);
// outcomes with NaN time were not solved and are skipped.
SweepRow SummarizeOutcomes(const ScenarioResult& s, const std::vector<PdOutcome>& outcomes);

}  // namespace pd_bench
