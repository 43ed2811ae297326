#include "bench/runs/pair_bench.h"

#include <set>

#include "bench/runs/fcl_baselines.h"
#include "bench/runs/pd_runner.h"
#include "bench/runs/reference_runner.h"

namespace pd_bench {
namespace {

// Indices of colliding cases.
std::vector<int> Colliding(const ScenarioResult& s) {
  std::vector<int> idx;
  for (size_t i = 0; i < s.cases.size(); ++i)
    if (s.cases[i].c.colliding) idx.push_back(static_cast<int>(i));
  return idx;
}

// k colliding cases spread over the scenario (over the path, for paths).
std::vector<int> Subset(const ScenarioResult& s, int k) {
  const std::vector<int> coll = Colliding(s);
  std::vector<int> idx;
  for (int i : SpreadIndices(static_cast<int>(coll.size()), k)) idx.push_back(coll[i]);
  return idx;
}

// Above st.large_tris triangles in all: fewer reference cases, no check.
bool IsLarge(const BenchPair& pair, const RunSettings& st) {
  return pair.probe->triangles + pair.scene->triangles > st.large_tris;
}

int RefCount(const BenchPair& pair, const RunSettings& st, Scenario s) {
  const bool large = IsLarge(pair, st);
  switch (s) {
    case Scenario::kRandom: return large ? st.ref_random_large : st.ref_random;
    case Scenario::kPath: return large ? st.ref_path_large : st.ref_path;
    case Scenario::kShallow: return large ? st.ref_shallow_large : st.ref_shallow;
  }
  return 0;
}

}  // namespace

bool RunSettings::Runs(Scenario s) const {
  if (scenarios.empty()) return true;
  for (const std::string& name : scenarios)
    if (name == ScenarioName(s)) return true;
  return false;
}

PairResult RunPair(const BenchPair& pair, const RunSettings& st) {
  PairResult out;
  out.pair = pair;
  const std::string tag = pair.name + ": ";

  std::vector<ScenarioCases> generated;
  {
    Progress bar(tag + "making cases", 3);
    if (st.Runs(Scenario::kRandom)) generated.push_back(RandomCases(pair, st.random_cases, st.seed));
    bar.Tick();
    if (st.Runs(Scenario::kPath) && !pair.random_only) generated.push_back(PathCases(pair, st.path_steps, st.seed + 1));
    bar.Tick();
    if (st.Runs(Scenario::kShallow) && !pair.random_only)
      generated.push_back(ShallowCases(pair, st.shallow_steps, st.shallow_depth_fraction,
                                       st.seed + 2));
  }

  // PolyDepth first, alone on the machine's cores, so its timings are clean.
  int total = 0;
  for (const ScenarioCases& g : generated) total += static_cast<int>(g.cases.size());
  {
    Progress bar(tag + "PolyDepth", total);
    for (const ScenarioCases& g : generated) {
      ScenarioResult s;
      s.scenario = g.scenario;
      s.description = g.description;
      s.steps_total = static_cast<int>(g.cases.size());
      const std::vector<PdOutcome> pd =
          RunPolyDepth(pair, g.cases, pd::PolyDepthOptions{}, g.scenario != Scenario::kRandom, &bar);
      for (size_t i = 0; i < g.cases.size(); ++i) {
        CaseRecord r;
        r.c = g.cases[i];
        r.pd = pd[i];
        s.cases.push_back(r);
      }
      out.scenarios.push_back(std::move(s));
    }
  }

  // Reference subsets; FCL runs on those plus an even spread of others.
  std::vector<std::vector<int>> ref_idx, fcl_idx;
  int fcl_total = 0, ref_total = 0;
  for (const ScenarioResult& s : out.scenarios) {
    ref_idx.push_back(Subset(s, RefCount(pair, st, s.scenario)));
    std::set<int> f(ref_idx.back().begin(), ref_idx.back().end());
    for (int i : Subset(s, st.fcl_cases)) f.insert(i);
    fcl_idx.emplace_back(f.begin(), f.end());
    fcl_total += static_cast<int>(f.size());
    ref_total += static_cast<int>(ref_idx.back().size());
  }

  {
    Progress bar(tag + "FCL baselines", fcl_total);
    const FclBaselines fcl(pair.probe->model->mesh(), pair.scene->model->mesh(),
                           st.fcl_max_contacts);
    out.probe_hull_vertices = fcl.probe_hull_vertices();
    out.scene_hull_vertices = fcl.scene_hull_vertices();
    out.hulls_consistent = fcl.hulls_consistent();
    const pd::Isometry3 X_WS = ScenePose(pair);
    for (size_t k = 0; k < out.scenarios.size(); ++k) {
      for (int i : fcl_idx[k]) {
        CaseRecord& r = out.scenarios[k].cases[i];
        const FclAnswer cv = fcl.ConvexHullPd(r.c.X_WP, X_WS);
        const FclAnswer mm = fcl.MeshContactPd(r.c.X_WP, X_WS);
        r.has_fcl = true;
        r.fcl = {cv.depth, cv.time_us, cv.in_collision, mm.depth, mm.time_us, mm.num_contacts,
                 mm.in_collision};
        bar.Tick();
      }
    }
  }

  {
    Progress bar(tag + "reference PD", ref_total);
    std::vector<RefJob> jobs;
    for (size_t k = 0; k < out.scenarios.size(); ++k)
      for (int i : ref_idx[k]) {
        CaseRecord& r = out.scenarios[k].cases[i];
        r.has_ref = true;
        jobs.push_back({&r.c, r.pd.translation_W, &r.ref});
      }
    RunReference(pair, jobs, st, &bar);
  }

  // The reference's own convergence: a sample of the random scenario's
  // reference cases again at the heavier check settings (small pairs only:
  // a large pair's reference takes a minute a case already).
  for (size_t k = 0; k < out.scenarios.size() && !IsLarge(pair, st) && st.ref_check_random > 0;
       ++k) {
    if (out.scenarios[k].scenario != Scenario::kRandom) continue;
    const std::vector<int>& refs = ref_idx[k];
    std::vector<RefJob> jobs;
    for (int j : SpreadIndices(static_cast<int>(refs.size()), st.ref_check_random)) {
      CaseRecord& r = out.scenarios[k].cases[refs[j]];
      r.has_ref_check = true;
      jobs.push_back({&r.c, r.pd.translation_W, &r.ref_check});
    }
    pd::ReferencePdOptions options;
    options.num_directions = st.ref_check_directions;
    options.refine_iterations = st.ref_check_refine_iterations;
    options.num_refine_starts = st.ref_check_refine_starts;
    Progress bar(tag + "reference check", static_cast<int>(jobs.size()));
    RunReference(pair, jobs, options, st.ref_threads, &bar);
  }
  return out;
}

}  // namespace pd_bench
