#include "bench/report/report_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "bench/runs/haptic_bench.h"
#include "bench/report/markdown_format.h"
#include "bench/report/observations.h"
#include "bench/report/published_numbers.h"
#include "bench/report/summaries.h"

namespace pd_bench {
namespace {

const char* PassMiss(bool pass) { return pass ? "PASS" : "**MISS**"; }

// "c / l / o / b / r" in percent, one digit.
std::string Shares(const WorkShares& w) {
  return Pct(w.collision, 0) + " / " + Pct(w.localisation, 0) + " / " +
         Pct(w.out_projection, 0) + " / " + Pct(w.list_builds, 0) + " / " + Pct(w.other, 0);
}

const ScenarioResult* Find(const PairResult& p, Scenario s) {
  for (const ScenarioResult& r : p.scenarios)
    if (r.scenario == s) return &r;
  return nullptr;
}

void MachineSection(const BenchRun& run, std::ostream& md) {
  const MachineInfo& m = run.machine;
  const RunSettings& st = run.settings;
  md << "| | |\n|---|---|\n"
     << "| CPU | " << m.cpu_model << " (" << m.num_cpus << " logical CPUs) |\n"
     << "| Date | " << m.date_utc << " |\n"
     << "| Commit | `" << m.git_commit << "` |\n"
     << "| Build type, CPU level | " << m.build_type << " (" << m.compiler << ") |\n"
     << "| Mode | " << (st.quick ? "--quick" : "full") << ", seed " << st.seed << " |\n"
     << "| Load average (1/5/15 min) | start " << m.load_average << ", end "
     << run.load_average_end << " |\n"
     << "| Run time | " << F(run.total_seconds, 0) << " s |\n\n";
  // Other work on a small machine inflates every wall-clock time here.
  const double load = std::max(std::atof(m.load_average.c_str()),
                               std::atof(run.load_average_end.c_str()));
  if (load > 0.75 * m.num_cpus)
    md << "**Note:** the 1-minute load average reached " << F(load, 2) << " on " << m.num_cpus
       << " CPUs during this run. It counts this run's own reference PD threads (all cores, "
          "run after each pair's timed passes) as well as other processes; times measured "
          "beside other work are inflated by contention: compare runs only at similar load.\n\n";
}

void SettingsSection(const BenchRun& run, std::ostream& md) {
  const RunSettings& st = run.settings;
  md << "## Setup\n\n"
     << "- Every model is scaled uniformly so that its bounding sphere (about its bounding-box "
        "centre) has radius "
     << kModelRadius << " m; probe and scene therefore have the same size. Scales are in the "
                        "model table. The scene sits with its box centre at the origin.\n";
  if (!run.pairs.empty())
    for (const ScenarioResult& s : run.pairs.front().scenarios)
      md << "- **" << ScenarioName(s.scenario) << "**: " << s.description << ".\n";
  md << "- Cases per pair: random " << st.random_cases << " (colliding ones kept), path "
     << st.path_steps << " steps, shallow path " << st.shallow_steps
     << " steps (statistics over colliding steps only).\n"
     << "- PolyDepth: default `PolyDepthOptions`; time = `result.time_us`. Validity = "
        "`result.valid` **and** `pd::InCollision` false at the returned translation "
        "(ModelPair offset in the scene frame). On reference cases the answer is also checked "
        "by `pd::ReferenceInCollision` (no code shared with the solver), and the reference's own "
        "answer (moved 1e-6 x pair size further out) by `pd::InCollision`.\n"
     << "- Reference PD (`pd::ReferencePenetrationDepth`, independent, no hint from PolyDepth): "
     << st.ref_directions << " Fibonacci directions, " << st.ref_refine_starts << " refinement starts x "
     << st.ref_refine_iterations << " evaluations; on " << st.ref_random << "/" << st.ref_path
     << "/" << st.ref_shallow << " (random/path/shallow) cases per pair, " << st.ref_random_large
     << "/" << st.ref_path_large << "/" << st.ref_shallow_large << " for pairs above "
     << st.large_tris << " triangles in total; spread evenly over the colliding cases; run on "
     << st.ref_threads << " threads after the timed PolyDepth runs.\n"
     << "- Relative error = (depth - ref) / ref. Both are upper bounds on the true PD, so a "
        "negative error means the reference missed a shallower escape that PolyDepth found. "
        "*Excess over best known* = (depth - b) / b with b = min(depth, ref): how far PolyDepth "
        "is above the best escape either method found (0 when PolyDepth is best).\n"
     << "- FCL baselines on the reference cases plus " << st.fcl_cases
     << " colliding cases spread over each scenario: (1) convex hulls (own quickhull) as "
        "`fcl::Convex`, GJK/EPA through `fcl::distance` with `enable_signed_distance` (libccd), "
        "depth = -distance (the hulls' PD: an upper bound on the meshes' PD); (2) "
        "`BVHModel<OBBRSS>` mesh-mesh `fcl::collide` with contacts (at most "
     << st.fcl_max_contacts << "), max `penetration_depth` over contacts.\n"
     << "- Knob sweep on the reference cases plus " << st.sweep_cases
     << " colliding cases spread over each scenario (the same cases in every row).\n"
     << "- *Pocket*: the answer is free but moving the probe a further "
     << F(100 * kPocketProbe, 1)
     << "% of its length along the same direction collides again, i.e. the answer sits in a "
        "thin pocket of free space rather than outside the scene.\n\n";
}

void TargetsSection(const BenchRun& run, std::ostream& md) {
  md << "## Project targets\n\n| Target | Pair / model | Scenario | Measured | PASS/MISS |\n"
        "|---|---|---|---|---|\n";
  for (const PairResult& p : run.pairs) {
    if (p.pair.name.find("knot") == std::string::npos) continue;
    if (const ScenarioResult* s = Find(p, Scenario::kRandom)) {
      const ScenarioSummary sum = Summarize(*s);
      md << "| cold knot-pair median <= " << F(kTargetColdKnotMedianUs / 1000, 1) << " ms | "
         << p.pair.name << " | random | " << F(sum.time_us.median / 1000, 3) << " ms | "
         << PassMiss(sum.time_us.median <= kTargetColdKnotMedianUs) << " |\n";
    }
  }
  // Cold queries: random configurations, errors on the reference cases
  // alone (PASS/MISS on the point estimates; the interval says how much a
  // few dozen cases can tell).
  for (const PairResult& p : run.pairs)
    if (const ScenarioResult* s = Find(p, Scenario::kRandom)) {
      const ScenarioSummary sum = Summarize(*s);
      const double p95_us = sum.time_us.p95;
      md << "| cold median <= " << F(kTargetColdMedianUs / 1000, 0) << " ms, p95 <= "
         << F(kTargetColdP95Us / 1000, 0) << " ms | " << p.pair.name << " | random ("
         << sum.n << " cases) | " << F(sum.time_us.median / 1000, 2) << " / "
         << F(p95_us / 1000, 2) << " ms | "
         << PassMiss(sum.time_us.median <= kTargetColdMedianUs && p95_us <= kTargetColdP95Us)
         << " |\n";
      md << "| cold mean \\|error\\| <= " << Pct(kTargetMeanError, 1) << ", p95 <= "
         << Pct(kTargetP95Error, 0) << ", max <= " << Pct(kTargetColdMaxError, 0) << " | "
         << p.pair.name << " | random (" << sum.n_ref << " ref cases) | "
         << Pct(sum.abs_error.mean) << " (95% CI "
         << PctRange(sum.abs_error_mean_ci.lo, sum.abs_error_mean_ci.hi) << ") / "
         << Pct(sum.abs_error.p95) << " / " << Pct(sum.abs_error.max) << " | "
         << PassMiss(sum.abs_error.mean <= kTargetMeanError &&
                     sum.abs_error.p95 <= kTargetP95Error &&
                     sum.abs_error.max <= kTargetColdMaxError)
         << " |\n";
    }
  for (const PairResult& p : run.pairs)
    for (Scenario sc : {Scenario::kPath, Scenario::kShallow}) {
      const ScenarioResult* s = Find(p, sc);
      if (!s) continue;
      const ScenarioSummary sum = Summarize(*s);
      md << "| coherent median <= " << F(kTargetCoherentMedianUs, 0) << " us, p99 <= "
         << F(kTargetCoherentP99Us, 0) << " us | " << p.pair.name << " | " << ScenarioName(sc)
         << " | " << F(sum.time_us.median) << " / " << F(sum.time_us.p99) << " us | "
         << PassMiss(sum.time_us.median <= kTargetCoherentMedianUs &&
                     sum.time_us.p99 <= kTargetCoherentP99Us)
         << " |\n";
    }
  for (const PairResult& p : run.pairs) {
    // Errors pooled over the pair's reference cases of all scenarios.
    std::vector<double> err;
    for (const ScenarioResult& s : p.scenarios)
      for (const CaseRecord& r : s.cases)
        if (r.c.colliding && r.has_ref) {
          const double e = RelativeError(r.pd.depth, r.ref.depth);
          if (!std::isnan(e)) err.push_back(std::fabs(e));
        }
    const double mean = Mean(err), p95 = Percentile(err, 95);
    md << "| mean \\|error\\| <= " << Pct(kTargetMeanError, 1) << ", p95 <= "
       << Pct(kTargetP95Error, 0) << " | " << p.pair.name << " | all (" << err.size()
       << " ref cases) | " << Pct(mean) << " / " << Pct(p95) << " | "
       << PassMiss(mean <= kTargetMeanError && p95 <= kTargetP95Error) << " |\n";
  }
  for (const auto& m : run.models) {
    const double bpt = static_cast<double>(m->memory_bytes) / m->triangles;
    md << "| precomputation < " << F(kTargetBytesPerTriangle, 0) << " B/triangle | " << m->name
       << " (" << m->triangles << " tris) | build | " << F(bpt) << " B/tri | "
       << PassMiss(bpt < kTargetBytesPerTriangle) << " |\n";
  }
  for (const auto& m : run.models) {
    if (m->triangles < 50000) continue;  // the target is about ~100k-triangle models
    const double per100k = m->build_ms * 100000.0 / m->triangles;
    md << "| build < " << F(kTargetBuildMsPer100k, 0) << " ms per 100k triangles | " << m->name
       << " (" << m->triangles << " tris) | build | " << F(m->build_ms) << " ms (" << F(per100k)
       << " ms per 100k) | " << PassMiss(per100k < kTargetBuildMsPer100k) << " |\n";
  }
  md << "\n";
}

void ModelsSection(const BenchRun& run, std::ostream& md) {
  md << "## Models and precomputation (`CollisionModel::Build`)\n\n"
        "| Model | Source | Scale (file units -> m) | Triangles | Closed | Build (ms, median) | "
        "Memory (KiB) | Bytes/triangle |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& m : run.models)
    md << "| " << m->name << " | " << m->source << " | " << G(m->scale) << " | " << m->triangles
       << " | " << (m->closed ? "yes" : "no") << " | " << F(m->build_ms) << " | "
       << F(m->memory_bytes / 1024.0, 0) << " | "
       << F(static_cast<double>(m->memory_bytes) / m->triangles) << " |\n";
  md << "\n";
  if (!run.skipped.empty()) {
    md << "Skipped pairs:\n\n";
    for (const std::string& s : run.skipped) md << "- " << s << "\n";
    md << "\n";
  }
}

void ResultsSection(const BenchRun& run, std::ostream& md) {
  md << "## PolyDepth results (default options)\n\n"
        "| Pair (probe vs scene tris) | Scenario | Cases | Median us | p90 us | p99 us | "
        "Max us | Iter. mean | Starts landed / iterated mean | Boxes / tris mean | Contacts mean | valid | verified free | pocket | Ref cases | "
        "ref-check free | mean \\|err\\| (95% CI) | p95 \\|err\\| | max \\|err\\| | signed mean | "
        "PD < ref | excess over best known: mean / max |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const PairResult& p : run.pairs)
    for (const ScenarioResult& s : p.scenarios) {
      const ScenarioSummary m = Summarize(s);
      md << "| " << p.pair.name << " (" << p.pair.probe->triangles << " vs "
         << p.pair.scene->triangles << ") | " << ScenarioName(s.scenario) << " | " << m.n
         << " | " << F(m.time_us.median) << " | " << F(m.time_us.p90) << " | " << F(m.time_us.p99)
         << " | " << F(m.time_us.max) << " | " << F(m.mean_iterations, 2) << " | "
         << F(m.mean_starts, 1) << " / " << F(m.mean_iterated_starts, 2) << " | "
         << F(m.mean_box_tests, 0) << " / " << F(m.mean_triangle_tests, 0) << " | "
         << F(m.mean_contacts, 1) << " | " << Pct(m.valid_rate, 1) << " | "
         << Pct(m.verified_rate, 1) << " | " << m.n_pocket << " | " << m.n_ref << " | "
         << Pct(m.ref_free_rate, 0)
         << " | " << Pct(m.abs_error.mean) << " ("
         << PctRange(m.abs_error_mean_ci.lo, m.abs_error_mean_ci.hi) << ") | "
         << Pct(m.abs_error.p95) << " | " << Pct(m.abs_error.max) << " | "
         << Pct(m.signed_mean_error) << " | " << m.n_below_ref
         << " | " << Pct(m.excess.mean) << " / " << Pct(m.excess.max) << " |\n";
    }
  md << "\nWhere a query's work goes, per scenario: each kind of pair query's share of the "
        "box and triangle tests (`result.work`) of the colliding cases. Cold (random) queries: "
        "collision = the query's test, the starts' and inner probes' tests and the "
        "verification; out-projection = the starts' landings and every iteration's CCD; "
        "localisation = every iteration's feature pairs; other = the support-plane starts:\n\n"
        "| Pair | Scenario | collision / localisation / out-projection / list builds / other |\n"
        "|---|---|---|\n";
  for (const PairResult& p : run.pairs)
    for (const ScenarioResult& s : p.scenarios)
      md << "| " << p.pair.name << " | " << ScenarioName(s.scenario) << " | "
         << Shares(Summarize(s).work) << " |\n";
  md << "\n";
}

// How far the reference itself is from converged: a sample of its random
// cases solved again at heavier settings (RunSettings::ref_check_random).
void ReferenceCheckSection(const BenchRun& run, std::ostream& md) {
  const RunSettings& st = run.settings;
  if (st.ref_check_random <= 0) return;
  md << "## The reference checked by a heavier one\n\n"
     << st.ref_check_random << " of each small pair's random reference cases (spread evenly) "
        "solved again by the reference at "
     << st.ref_check_directions << " directions, " << st.ref_check_refine_starts
     << " refinement starts x " << st.ref_check_refine_iterations
     << " evaluations (the run's reference: " << st.ref_directions << ", "
     << st.ref_refine_starts << " x " << st.ref_refine_iterations
     << "). Both are upper bounds on the true PD: *reference above the check* = (ref - check) / "
        "check is how much the reference itself missed on these cases (a lower bound on its "
        "error). PolyDepth's |error| on the same cases against each.\n\n"
        "| Pair | Cases | reference above the check: mean / max | check shorter by > 0.1% | "
        "PolyDepth \\|err\\| vs reference: mean / max | vs check: mean / max | check time median |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const PairResult& p : run.pairs) {
    const ScenarioResult* s = Find(p, Scenario::kRandom);
    if (s == nullptr) continue;
    const ScenarioSummary m = Summarize(*s);
    if (m.n_ref_check == 0) continue;
    md << "| " << p.pair.name << " | " << m.n_ref_check << " | " << Pct(m.ref_over_check.mean)
       << " / " << Pct(m.ref_over_check.max) << " | " << m.n_check_below_ref << " | "
       << Pct(m.abs_error_on_check_cases.mean) << " / " << Pct(m.abs_error_on_check_cases.max)
       << " | " << Pct(m.abs_error_vs_check.mean) << " / " << Pct(m.abs_error_vs_check.max)
       << " | " << F(m.ref_check_time_ms.median / 1000.0, 1) << " s |\n";
  }
  md << "\n";
}

void BaselinesSection(const BenchRun& run, std::ostream& md) {
  md << "## Baselines on the same cases\n\n"
        "Time ratio = median baseline time / median PolyDepth time on the same cases (> 1: "
        "the baseline is slower). Errors against the reference PD on the reference cases.\n\n"
        "| Pair | Scenario | Method | Cases | Median time | Time ratio | Ref cases | "
        "mean \\|err\\| | p95 \\|err\\| | max \\|err\\| | signed mean | reported no collision |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const PairResult& p : run.pairs)
    for (const ScenarioResult& s : p.scenarios) {
      const ScenarioSummary m = Summarize(s);
      const std::string head = "| " + p.pair.name + " | " + ScenarioName(s.scenario) + " | ";
      md << head << "PolyDepth | " << m.n << " | " << F(m.time_us.median) << " us | 1 | "
         << m.n_ref << " | " << Pct(m.abs_error.mean) << " | " << Pct(m.abs_error.p95) << " | "
         << Pct(m.abs_error.max) << " | " << Pct(m.signed_mean_error) << " | 0 |\n";
      md << head << "reference PD | " << m.n_ref << " | " << F(m.ref_time_ms.median) << " ms | "
         << G(m.ref_time_ratio) << " | " << m.n_ref << " | 0 (is the reference) | - | - | - | - |\n";
      const std::pair<const char*, const BaselineSummary*> rows[] = {
          {"FCL GJK/EPA on convex hulls", &m.fcl_convex},
          {"FCL mesh-mesh contacts (max depth)", &m.fcl_mesh}};
      for (const auto& [name, b] : rows)
        md << head << name << " | " << b->n << " | " << F(b->time_us.median) << " us | "
           << G(b->time_ratio) << " | " << b->n_ref << " | " << Pct(b->abs_error.mean, 1)
           << " | " << Pct(b->abs_error.p95, 1) << " | " << Pct(b->abs_error.max, 1) << " | "
           << Pct(b->signed_mean_error, 1) << " | " << b->n_no_collision << " |\n";
    }
  md << "\nConvex hulls (vertices, probe / scene):";
  for (const PairResult& p : run.pairs)
    md << " " << p.pair.name << " " << p.probe_hull_vertices << " / " << p.scene_hull_vertices
       << (p.hulls_consistent ? "" : " (quickhull not watertight: FCL falls back to a vertex scan)")
       << ";";
  md << "\n\n";
}

void PaperSection(const BenchRun& run, std::ostream& md) {
  md << "## Published PolyDepth timings (Je et al. 2012, random configurations, 2012 "
        "hardware) beside this run\n\n"
        "The paper's models are not all available here; each row is paired with the measured "
        "pair closest in triangle count (larger of probe and scene).\n\n"
        "| Paper model | Paper tris | Paper ms/query | Paper iterations | Closest pair here | "
        "Tris (probe / scene) | Measured median ms (random, cold) | Measured mean ms | "
        "Measured iterations |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const PaperTiming& t : kPaperTimings) {
    const PairResult* best = nullptr;
    double best_gap = 1e300;
    for (const PairResult& p : run.pairs) {
      const int tris = std::max(p.pair.probe->triangles, p.pair.scene->triangles);
      const double gap = std::fabs(std::log(static_cast<double>(tris) / t.triangles));
      if (gap < best_gap) best_gap = gap, best = &p;
    }
    md << "| " << t.model << " | " << t.triangles << " | " << F(t.ms_per_query, 2) << " | "
       << (t.iterations < 0 ? std::string("-") : F(t.iterations, 2)) << " | ";
    const ScenarioResult* s = best ? Find(*best, Scenario::kRandom) : nullptr;
    if (!s) {
      md << "- | - | - | - | - |\n";
      continue;
    }
    const ScenarioSummary m = Summarize(*s);
    md << best->pair.name << " | " << best->pair.probe->triangles << " / "
       << best->pair.scene->triangles << " | " << F(m.time_us.median / 1000, 3) << " | "
       << F(m.time_us.mean / 1000, 3) << " | " << F(m.mean_iterations, 2) << " |\n";
  }
  md << "\n";
}

void SweepSection(const BenchRun& run, std::ostream& md) {
  md << "## Knob sweep (speed against error)\n\n"
        "One `PolyDepthOptions` field changed at a time from the defaults. Random cases are "
        "solved cold; `warm_start` on/off on the coherent paths. Errors on the reference "
        "cases of that scenario.\n\n"
        "| Pair | Scenario | Configuration | Cases | Median us | p90 us | Iter. mean | valid | "
        "Ref cases | mean \\|err\\| | p95 \\|err\\| | signed mean |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SweepRow& r : run.sweep)
    md << "| " << r.pair << " | " << ScenarioName(r.scenario) << " | " << r.config << " | "
       << r.n << " | " << F(r.median_us) << " | " << F(r.p90_us) << " | "
       << F(r.mean_iterations, 2) << " | " << Pct(r.valid_rate, 1) << " | " << r.n_ref << " | "
       << Pct(r.mean_abs_error) << " | " << Pct(r.p95_abs_error) << " | "
       << Pct(r.signed_mean_error) << " |\n";
  md << "\n";
}

// Targets of the warm-PD issue, measured on the haptic paths.
constexpr double kHapticMedianRatio = 2.0, kHapticP99Ratio = 10.0, kHapticMaxUs = 1000.0;
constexpr double kHapticMeanError = 0.01;

void HapticSection(const BenchRun& run, std::ostream& md) {
  if (run.haptic.empty()) return;
  // One summary per pair, for the three tables below.
  std::vector<HapticSummary> summaries;
  for (const HapticPairResult& r : run.haptic) summaries.push_back(SummarizeHaptic(r));
  md << "## Haptic scenario: a mesh tool sliding over a mesh object\n\n"
     << "What the servo loop asks of PolyDepth: one warm-started query per millisecond while a "
        "mesh tool (bounding radius "
     << F(kHapticToolRadius * 100, 1) << " cm) slides over a mesh object (radius "
     << F(kHapticObjectRadius * 100, 1)
     << " cm), turning, a set depth below first contact, losing and regaining contact (two 1 mm "
        "lift-offs per path; a hand that digs in more than 1 mm too deep stops sliding until it "
        "has climbed back). "
     << run.settings.haptic_steps << " poses per path. Time = `result.time_us` of the answer, over "
        "the colliding poses, with default `PolyDepthOptions` but for `defer_list_builds`, as the "
        "server's geometry thread runs PolyDepth: a query whose candidate list no longer covers "
        "it answers without a new one and rebuilds it after the answer (`PrepareNext`, until the "
        "next pose is due 1 ms after the query began; the table after this one gives that work "
        "and the same path with the rebuilds inside the queries); FCL = `fcl::collide` of "
        "`BVHModel<OBB>` meshes (boolean, first contact) at the same poses, measured in the same "
        "run after PolyDepth: the cost of a collision test, the yardstick for a warm PD query. "
        "Cold restarts = colliding poses after the first where no coherent start gave an answer; "
        "cross-checks = queries that ran part of the check of a coherent answer grown much deeper "
        "than its anchor (free directions around the query inside the answer's length, four per "
        "query; a shorter answer on the same side wins), or one probe back along the anchor's "
        "direction when the answer has turned from it while growing. An answer counts as free "
        "only if the tool is also free "
     << G(kHapticFreeMargin) << " x pair size further out along it. Reference: "
     << run.settings.haptic_ref << " colliding poses per path, spread evenly, no hint ("
     << run.settings.haptic_ref_directions << " directions, " << run.settings.ref_refine_starts
     << " refinement starts x " << run.settings.haptic_ref_refine_iterations
     << " evaluations). Max by "
        "depth: the colliding poses whose answer is within "
     << F(kHapticTargetMaxDepth * 1e3, 0)
     << " mm (the depth range the warm targets are set for) and the deeper ones, where a path "
        "digs into a thin part.\n\n";
  md << "| Pair | Tool / object tris | Motion | Poses (colliding) | PD median / p99 / p99.9 / max us "
        "| max us: PD <= " << F(kHapticTargetMaxDepth * 1e3, 0) << " mm / deeper (poses deeper) "
        "| FCL collide median / p99 us | ratio median / p99 | free-pose median / max us | iter. | "
        "boxes / tris per query | cold restarts (cross-checks) | not converged | not free (+margin) | ref | "
        "mean / max \\|err\\| |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < run.haptic.size(); ++i) {
    const HapticPairResult& r = run.haptic[i];
    const HapticSummary& m = summaries[i];
    md << "| " << r.spec.name << " | " << r.pair.probe->triangles << " / " << r.pair.scene->triangles
       << " | " << F(r.spec.speed_m_s, 2) << " m/s, " << F(r.spec.turn_deg_s, 0) << " deg/s, "
       << F(r.spec.depth_m * 1e3, 1) << " mm | " << m.steps << " (" << m.colliding << ") | "
       << F(m.pd_us.median) << " / " << F(m.pd_us.p99) << " / " << F(m.p999_us) << " / "
       << F(m.pd_us.max) << " | " << F(m.in_range_us.max) << " / "
       << (m.deeper_us.n > 0 ? F(m.deeper_us.max) : std::string("-")) << " (" << m.deeper_us.n
       << ") | " << F(m.fcl_us.median) << " / " << F(m.fcl_us.p99) << " | "
       << F(m.median_ratio, 2) << " / " << F(m.p99_ratio, 2) << " | " << F(m.pd_free_us.median)
       << " / " << F(m.pd_free_us.max) << " | " << F(m.mean_iterations, 2) << " | " << F(m.mean_box_tests, 0) << " / "
       << F(m.mean_triangle_tests, 0) << " | " << m.cold_restarts << " (" << m.cross_checks
       << ") | " << m.not_converged
       << " | " << m.invalid << " (" << m.not_free_beyond << ") | " << m.n_ref << " | "
       << Pct(m.abs_error.mean) << " / " << Pct(m.abs_error.max) << " |\n";
  }
  if (run.settings.haptic_budget_us > 0.0) {
    md << "\nBounded time, the geometry thread's mode: the same paths solved again by a second "
          "warm-started solver with `PolyDepthOptions::max_time_us` = "
       << F(run.settings.haptic_budget_us, 0)
       << " us (the server's default `geometry_budget_ms`). A query that reaches the budget "
          "answers its best verified-free translation so far, marked not converged, and the next "
          "query goes on from it; the search stops at 85% of the budget and leaves the rest to "
          "the answer's own checks (polydepth.h, max_time_us). Errors on the same "
          "reference poses as above:\n\n"
          "| Pair | PD median / p99 / max us | stopped by the budget | not free (+margin) | "
          "mean / max \\|err\\| |\n|---|---|---|---|---|\n";
    for (size_t i = 0; i < run.haptic.size(); ++i) {
      const HapticSummary& m = summaries[i];
      if (!m.has_budget) continue;
      md << "| " << run.haptic[i].spec.name << " | " << F(m.budget_us.median) << " / "
         << F(m.budget_us.p99) << " / " << F(m.budget_us.max) << " | " << m.budget_not_converged
         << " of " << m.budget_us.n << " | " << m.budget_not_free << " | "
         << Pct(m.budget_abs_error.mean) << " / " << Pct(m.budget_abs_error.max) << " |\n";
    }
  }
  std::vector<HapticPathsSummary> paths;
  for (const HapticPairResult& r : run.haptic)
    paths.push_back(SummarizeHapticPaths(r, kHapticMaxUs));
  if (run.settings.haptic_more_paths > 0) {
    md << "\nThe max of one path depends on that path (where its basin switches fall). Each "
          "pair again on "
       << run.settings.haptic_more_paths
       << " more paths of the same kind (other seeds), solved the same two ways, every answer "
          "checked free (+margin); no FCL and no reference there. Max per path: the first path's "
          "first (the tables above), then the others; over all "
       << 1 + run.settings.haptic_more_paths << " paths:\n\n"
          "| Pair | colliding poses | max us per path | paths over "
       << F(kHapticMaxUs, 0) << " us | max us, PD <= " << F(kHapticTargetMaxDepth * 1e3, 0)
       << " mm | worst p99 us | max work (tests) | cold restarts | not free (+margin) | "
          "bounded: max us per path | bounded: paths over "
       << F(kHapticMaxUs, 0)
       << " us | bounded: max CPU us per path | stopped by the budget | bounded: not free |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (size_t i = 0; i < run.haptic.size(); ++i) {
      const HapticPathsSummary& m = paths[i];
      auto list = [](const std::vector<double>& v) {
        std::string s;
        for (size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + F(v[k], 0);
        return s.empty() ? std::string("-") : s;
      };
      md << "| " << run.haptic[i].spec.name << " | " << m.colliding << " | " << list(m.max_us)
         << " | " << m.paths_over_target << " of " << m.paths << " | " << F(m.in_range_max_us)
         << " | " << F(m.worst_p99_us) << " | " << F(m.max_work, 0) << " | " << m.cold_restarts
         << " | " << m.not_free << " | " << list(m.budget_max_us) << " | "
         << m.budget_paths_over_target << " of " << m.budget_max_us.size() << " | "
         << list(m.budget_cpu_max_us) << " | " << m.budget_stopped << " | " << m.budget_not_free
         << " |\n";
    }
    md << "\nWall time against CPU time: a query's time above is wall-clock; its CPU time "
          "(the thread's, `CLOCK_THREAD_CPUTIME_ID`, read around `Solve`) leaves out the time "
          "the thread was preempted, so a max far above its CPU time is a stall of the machine. "
          "The converse does not hold on a VM: a vCPU the host slows or steals from without "
          "reporting it charges that time to the running thread (haptic_work on this machine: "
          "queries of 141-681 box and triangle tests charged 1.2-2.0 ms of CPU with no page "
          "fault or context switch); the max work per path (tests) is the machine-independent "
          "measure. Over all paths, max CPU us unbounded / bounded: ";
    for (size_t i = 0; i < run.haptic.size(); ++i)
      md << (i ? "; " : "") << run.haptic[i].spec.name << " " << F(paths[i].cpu_max_us_all, 0)
         << " / " << F(paths[i].budget_cpu_max_us_all, 0);
    md << ".\n";
  }
  md << "\nAnswer first, rebuild after. A warm query keeps a list of the leaf-pair boxes near "
        "the contact and reuses it while the tool stays within its reach; a query that slid out "
        "of it (or whose iterate moved millimetres away) needs a new one, built by descending "
        "both hierarchies around the contact. Built inside that query, the rebuilds set the "
        "tail: the comparison pass below solves the same path with `defer_list_builds` off "
        "(the times of its colliding queries that rebuilt and of those that did not, the "
        "rebuilds' share of its time, how many of its slowest 1% rebuilt). Deferred, the "
        "query answers without the new list (descending the hierarchies where the old one does "
        "not reach; the same answers) and `PrepareNext` builds it after the answer, around it, "
        "in the rest of the millisecond; a build that does not fit is paused by the next pose "
        "and goes on after that pose's answer. Busy = answer plus `PrepareNext`, per colliding "
        "pose: the geometry thread's time per millisecond.\n\n"
        "| Pair | rebuilt in the query: median / p99 / max us | answers, rebuilds deferred: "
        "median / p99 / max us | p99 ratio (deferred / in the query) | busy median / p99 / max us "
        "| rebuilds completed after answers (paused by the next pose) | in the query: queries that "
        "rebuilt | their median / p99 us | the others' median / p99 us | rebuilds' share of its "
        "time | its slowest 1% that rebuilt |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < run.haptic.size(); ++i) {
    const HapticPairResult& r = run.haptic[i];
    const HapticSummary& m = summaries[i];
    md << "| " << r.spec.name << " | " << F(m.inquery_us.median) << " / " << F(m.inquery_us.p99)
       << " / " << F(m.inquery_us.max) << " | " << F(m.pd_us.median) << " / " << F(m.pd_us.p99)
       << " / " << F(m.pd_us.max) << " | " << F(m.pd_us.p99 / m.inquery_us.p99, 2) << " | "
       << F(m.busy_us.median) << " / " << F(m.busy_us.p99) << " / " << F(m.busy_us.max) << " | "
       << m.lists_completed << " (" << m.prepare_paused << ") | " << m.with_build_us.n << " of "
       << m.inquery_us.n << " ("
       << Pct(m.inquery_us.n > 0 ? static_cast<double>(m.with_build_us.n) / m.inquery_us.n : kNaN, 0)
       << ") | " << F(m.with_build_us.median) << " / " << F(m.with_build_us.p99) << " | "
       << F(m.without_build_us.median) << " / " << F(m.without_build_us.p99) << " | "
       << Pct(m.build_time_share, 0) << " | " << m.inquery_slowest_1pct_with_build << " of "
       << m.inquery_slowest_1pct << " |\n";
  }
  md << "\nWhere the work goes: each kind of pair query's share of the box and triangle tests "
        "(`result.work`) of all colliding queries and of the slowest 1% by time. Collision = "
        "collision tests (the query's own, the cross-check's probes, the verification); "
        "localisation = feature pairs near a configuration (step 0's free test-and-localise "
        "included); out-projection = translational CCD; list builds = the leaf-pair lists (none "
        "inside a deferring query); "
        "other = the PD lower bound that lets a check skip its probes (depth_lower_bound.h):\n\n"
        "| Pair | all colliding: collision / localisation / out-projection / list builds / other "
        "| slowest 1%: collision / localisation / out-projection / list builds / other |\n"
        "|---|---|---|\n";
  for (size_t i = 0; i < run.haptic.size(); ++i)
    md << "| " << run.haptic[i].spec.name << " | " << Shares(summaries[i].work) << " | "
       << Shares(summaries[i].slowest_1pct_work) << " |\n";
  md << "\n| Target (haptic paths) | Pair | Measured | PASS/MISS |\n|---|---|---|---|\n";
  for (size_t i = 0; i < run.haptic.size(); ++i) {
    const HapticPairResult& r = run.haptic[i];
    const HapticSummary& m = summaries[i];
    // The bounded pass's max over every path, by wall time ("") or another
    // measure of it (what).
    auto bounded_row = [&](const std::string& what, double max_us, int paths_over) {
      return "| max <= " + F(kHapticMaxUs, 0) + " us" + what + ", bounded at " +
             F(run.settings.haptic_budget_us, 0) + " us, every path (" +
             std::to_string(paths[i].budget_max_us.size()) + ") | " + r.spec.name + " | " +
             F(max_us) + " us | " + PassMiss(paths_over == 0) + " |\n";
    };
    md << "| median <= " << F(kHapticMedianRatio, 0) << "x FCL collide | " << r.spec.name << " | "
       << F(m.median_ratio, 2) << "x | " << PassMiss(m.median_ratio <= kHapticMedianRatio) << " |\n"
       << "| p99 <= " << F(kHapticP99Ratio, 0) << "x FCL collide p99 | " << r.spec.name << " | "
       << F(m.p99_ratio, 2) << "x | " << PassMiss(m.p99_ratio <= kHapticP99Ratio) << " |\n"
       << "| max <= " << F(kHapticMaxUs, 0) << " us | " << r.spec.name << " | " << F(m.pd_us.max)
       << " us | " << PassMiss(m.pd_us.max <= kHapticMaxUs) << " |\n"
       << "| max <= " << F(kHapticMaxUs, 0) << " us, poses with PD <= "
       << F(kHapticTargetMaxDepth * 1e3, 0) << " mm | " << r.spec.name << " | "
       << F(m.in_range_us.max) << " us (" << m.in_range_us.n << " poses) | "
       << PassMiss(m.in_range_us.max <= kHapticMaxUs) << " |\n"
       << (paths[i].paths > 1
               ? "| max <= " + F(kHapticMaxUs, 0) + " us, every path (" +
                     std::to_string(paths[i].paths) + ") | " + r.spec.name + " | " +
                     F(paths[i].max_us_all) + " us (" + std::to_string(paths[i].paths_over_target) +
                     " over) | " + PassMiss(paths[i].paths_over_target == 0) + " |\n"
               : std::string())
       << (paths[i].budget_max_us.size() > 0
               ? bounded_row("", paths[i].budget_max_us_all, paths[i].budget_paths_over_target) +
                     bounded_row(" of CPU time", paths[i].budget_cpu_max_us_all,
                                 paths[i].budget_cpu_paths_over_target)
               : std::string())
       << "| no cold restart | " << r.spec.name << " | " << m.cold_restarts << " | "
       << PassMiss(m.cold_restarts == 0) << " |\n"
       << "| every answer free (+" << G(kHapticFreeMargin) << " x size) | " << r.spec.name
       << " | " << m.not_free_beyond << " not | " << PassMiss(m.not_free_beyond == 0) << " |\n"
       << "| mean \\|error\\| <= " << Pct(kHapticMeanError, 0) << " | " << r.spec.name << " | "
       << Pct(m.abs_error.mean) << " (" << m.n_ref << " ref) | "
       << PassMiss(m.abs_error.mean <= kHapticMeanError) << " |\n";
  }
  md << "\n";
}

void FilesSection(const std::vector<std::string>& csv_files,
                  const std::vector<std::string>& png_files, std::ostream& md) {
  md << "## Files\n\n";
  for (const std::string& f : csv_files) md << "- [" << f << "](" << f << ")\n";
  for (const std::string& f : png_files) md << "- [" << f << "](" << f << "): ![" << f << "](" << f << ")\n";
  if (!png_files.empty()) md << "- pd_plots.gp: the gnuplot script (data inline) behind the plots\n";
}

}  // namespace

void WriteMarkdownReport(const BenchRun& run, const std::string& path,
                         const std::vector<std::string>& csv_files,
                         const std::vector<std::string>& png_files) {
  std::ofstream md(path);
  if (!md) throw std::runtime_error("cannot write " + path);
  md << "# PolyDepth speed against error\n\n"
        "Generated by `build/bin/bench_pd` (bench/apps/bench_pd.cc); every number below was "
        "measured in this run except the paper's published timings and the targets. "
        "Regenerate with `bench/run_pd_bench.sh"
     << (run.settings.quick ? " --quick" : "") << "`.\n\n";
  MachineSection(run, md);
  TargetsSection(run, md);
  SettingsSection(run, md);
  ModelsSection(run, md);
  HapticSection(run, md);
  ResultsSection(run, md);
  ReferenceCheckSection(run, md);
  BaselinesSection(run, md);
  PaperSection(run, md);
  SweepSection(run, md);
  WriteObservations(run, md);
  FilesSection(csv_files, png_files, md);
}

void WriteHapticReport(const BenchRun& run, const std::string& path,
                       const std::vector<std::string>& csv_files,
                       const std::vector<std::string>& png_files) {
  std::ofstream md(path);
  if (!md) throw std::runtime_error("cannot write " + path);
  md << "# Warm PolyDepth at haptic rates\n\n"
        "Generated by `build/bin/bench_pd --haptic-only"
     << (run.settings.quick ? " --quick" : "")
     << "` (bench/apps/bench_pd.cc); every number below was measured in this run. The full "
        "benchmark (`bench/run_pd_bench.sh`) includes this section in pd_speed_error.md.\n\n";
  MachineSection(run, md);
  HapticSection(run, md);
  FilesSection(csv_files, png_files, md);
}

}  // namespace pd_bench
