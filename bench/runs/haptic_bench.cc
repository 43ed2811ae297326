#include "bench/runs/haptic_bench.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "bench/runs/answer_free.h"
#include "bench/runs/fcl_baselines.h"
#include "bench/common/progress.h"
#include "bench/runs/reference_runner.h"
#include "haptics/loop/monotonic_clock.h"
#include "bench/report/summaries.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/polydepth/polydepth.h"

namespace pd_bench {

namespace {

// Solves `path` with one warm-started solver as the server's geometry thread
// does: each answer first, then the list rebuild it deferred (PrepareNext)
// until the next pose is due, a millisecond after the answer's query began.
// on_answer(case, result, preparation, cpu_us) after each pose, cpu_us the
// query's CPU time (the thread's, read around Solve: its wall time
// result.time_us less any time the thread was preempted; a vCPU the host
// slows or steals from unreported is still charged; the read itself, a
// system call, adds ~1 us).
template <typename OnAnswer>
void SolveAlongPath(const BenchPair& pair, const HapticPath& path, const pd::Isometry3& X_WS,
                    const pd::PolyDepthOptions& options, OnAnswer&& on_answer) {
  pd::PolyDepthSolver solver(pair.probe->model, pair.scene->model, options);
  for (const Case& c : path.cases) {
    const int64_t cpu0_ns = haptics::ThreadCpuNowNs();
    const pd::PenetrationResult r = solver.Solve(c.X_WP, X_WS, /*coherent=*/true);
    const double cpu_us = 1e-3 * static_cast<double>(haptics::ThreadCpuNowNs() - cpu0_ns);
    const auto t0 = std::chrono::steady_clock::now();
    const double left_us = kHapticPosePeriodUs - r.time_us;
    const pd::PolyDepthSolver::Preparation p = solver.PrepareNext([&] {
      return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0)
                 .count() >= left_us;
    });
    on_answer(c, r, p, cpu_us);
  }
}

}  // namespace

HapticPairResult RunHapticPair(const BenchPair& pair, const HapticPairSpec& spec,
                               const RunSettings& st) {
  HapticPairResult out;
  out.spec = spec;
  out.pair = pair;
  const std::string tag = spec.name + ": ";
  HapticPath path;
  {
    Progress bar(tag + "making the haptic path", 1);
    out.path_seed = HapticPathSeed(st.seed);
    path = MakeHapticPath(pair, spec, st.haptic_steps, out.path_seed);
  }
  out.description = path.description;
  const pd::Isometry3 X_WS = ScenePose(pair);

  // PolyDepth alone first, one warm-started solver for the whole path, as
  // the server's geometry thread runs it (SolveAlongPath).
  pd::PolyDepthOptions deferring;
  deferring.defer_list_builds = true;
  {
    Progress bar(tag + "PolyDepth (haptic)", static_cast<int>(path.cases.size()));
    bool previous_seen = false;
    SolveAlongPath(pair, path, X_WS, deferring, [&](const Case& c, const pd::PenetrationResult& r,
                                                     const pd::PolyDepthSolver::Preparation& p,
                                                     double cpu_us) {
      HapticStep s;
      s.c = c;
      s.cpu_us = cpu_us;
      s.pd.in_collision = r.in_collision;
      s.pd.valid = r.valid;
      s.pd.depth = r.depth;
      s.pd.time_us = r.time_us;
      s.pd.iterations = r.iterations;
      s.pd.contacts = r.num_contacts;
      s.pd.initializer = pd::InitializerName(r.initializer);
      s.pd.translation_W = r.translation_W;
      s.converged = r.converged;
      s.box_tests = static_cast<double>(r.box_tests);
      s.triangle_tests = static_cast<double>(r.triangle_tests);
      s.pd.work = r.work;
      s.cold_restart = previous_seen && r.in_collision && r.warm_start_failed;
      s.cross_checked = r.cross_checked;
      s.prepare_us = p.time_us;
      s.prepare_box_tests = static_cast<double>(p.box_tests);
      s.lists_completed = p.lists_completed;
      s.prepare_paused = !p.done;
      previous_seen = true;
      out.steps.push_back(s);
      bar.Tick();
    });
  }
  // The comparison: the same path with the rebuilds inside the queries.
  {
    Progress bar(tag + "PolyDepth (haptic, lists rebuilt in the query)",
                 static_cast<int>(out.steps.size()));
    pd::PolyDepthSolver solver(pair.probe->model, pair.scene->model, pd::PolyDepthOptions{});
    for (HapticStep& s : out.steps) {
      const pd::PenetrationResult r = solver.Solve(s.c.X_WP, X_WS, /*coherent=*/true);
      s.inquery_time_us = r.time_us;
      s.inquery_in_collision = r.in_collision;
      s.list_builds = r.list_builds;
      s.list_build_us = r.list_build_us;
      bar.Tick();
    }
  }
  // The same path again in bounded time (the geometry thread's mode): each
  // query stops at the budget with its best verified-free answer so far and
  // the next goes on from it (and rebuilds deferred as above).
  pd::PolyDepthOptions bounded = deferring;
  bounded.max_time_us = st.haptic_budget_us;
  if (st.haptic_budget_us > 0.0) {
    Progress bar(tag + "PolyDepth (haptic, bounded time)", static_cast<int>(out.steps.size()));
    size_t i = 0;
    SolveAlongPath(pair, path, X_WS, bounded, [&](const Case&, const pd::PenetrationResult& r,
                                                   const pd::PolyDepthSolver::Preparation&,
                                                   double cpu_us) {
      HapticStep& s = out.steps[i++];
      s.has_budget = true;
      s.budget_cpu_us = cpu_us;
      s.budget_in_collision = r.in_collision;
      s.budget_converged = r.converged;
      s.budget_free = r.valid;  // and verified below
      s.budget_depth = r.depth;
      s.budget_time_us = r.time_us;
      s.budget_translation_W = r.translation_W;
      bar.Tick();
    });
  }
  // More paths (other seeds): times and work, unbounded and bounded, every
  // answer checked free; no FCL, no reference.
  {
    Progress bar(tag + "PolyDepth (haptic, more paths)", st.haptic_more_paths);
    for (int k = 1; k <= st.haptic_more_paths; ++k) {
      HapticPathRun run;
      run.path_seed = HapticPathSeed(st.seed + k);
      const HapticPath more = MakeHapticPath(pair, spec, st.haptic_steps, run.path_seed);
      auto free_answer = [&](const Case& c, const pd::PenetrationResult& r) {
        const pd::ModelPair mp(*pair.probe->model, *pair.scene->model, c.X_WP, X_WS);
        return r.valid && AnswerFreeBeyond(mp, X_WS.linear().transpose() * r.translation_W);
      };
      bool previous_seen = false;
      SolveAlongPath(pair, more, X_WS, deferring, [&](const Case& c, const pd::PenetrationResult& r,
                                                       const pd::PolyDepthSolver::Preparation&,
                                                       double cpu_us) {
        const bool seen = previous_seen;
        previous_seen = true;
        if (!r.in_collision) return;
        run.us.push_back(r.time_us);
        run.cpu_us.push_back(cpu_us);
        run.work.push_back(static_cast<double>(r.box_tests + r.triangle_tests));
        run.depth.push_back(r.depth);
        run.cold_restarts += seen && r.warm_start_failed;
        run.not_free += !free_answer(c, r);
      });
      if (st.haptic_budget_us > 0.0)
        SolveAlongPath(pair, more, X_WS, bounded, [&](const Case& c, const pd::PenetrationResult& r,
                                                       const pd::PolyDepthSolver::Preparation&,
                                                       double cpu_us) {
          if (!r.in_collision) return;
          run.budget_us.push_back(r.time_us);
          run.budget_cpu_us.push_back(cpu_us);
          run.budget_stopped += !r.converged;
          run.budget_not_free += !free_answer(c, r);
        });
      out.more_paths.push_back(std::move(run));
      bar.Tick();
    }
  }
  // Checks and FCL, outside PolyDepth's clock.
  {
    Progress bar(tag + "checks and FCL collide", static_cast<int>(out.steps.size()));
    const FclBaselines fcl(pair.probe->model->mesh(), pair.scene->model->mesh(), 1);
    for (HapticStep& s : out.steps) {
      const pd::ModelPair mp(*pair.probe->model, *pair.scene->model, s.c.X_WP, X_WS);
      const pd::Vector3 q_S = X_WS.linear().transpose() * s.pd.translation_W;
      s.pd.verified_free = !pd::InCollision(mp, q_S);
      s.free_beyond = s.pd.verified_free && FreeFurtherAlong(mp, q_S);
      if (s.has_budget && s.budget_in_collision && s.budget_free) {
        const pd::Vector3 b_S = X_WS.linear().transpose() * s.budget_translation_W;
        s.budget_free = AnswerFreeBeyond(mp, b_S);
      }
      const FclAnswer a = fcl.Collide(s.c.X_WP, X_WS);
      s.fcl_time_us = a.time_us;
      s.fcl_collide = a.in_collision;
      bar.Tick();
    }
  }
  // Reference on a spread of colliding poses, without any hint.
  std::vector<int> colliding;
  for (size_t i = 0; i < out.steps.size(); ++i)
    if (out.steps[i].c.colliding) colliding.push_back(static_cast<int>(i));
  std::vector<RefJob> jobs;
  for (int k : SpreadIndices(static_cast<int>(colliding.size()), st.haptic_ref)) {
    HapticStep& s = out.steps[colliding[k]];
    s.has_ref = true;
    jobs.push_back({&s.c, s.pd.translation_W, &s.ref});
  }
  {
    Progress bar(tag + "reference PD (haptic)", static_cast<int>(jobs.size()));
    RunReference(pair, jobs, st, &bar, /*haptic=*/true);
  }
  return out;
}

HapticSummary SummarizeHaptic(const HapticPairResult& r) {
  HapticSummary m;
  std::vector<double> pd_us, free_us, fcl_us, iters, boxes, tris, err, signed_err;
  std::vector<double> with_build_us, without_build_us, budget_us, budget_err;
  std::vector<const HapticStep*> by_time;  // colliding queries (sorted slowest first below)
  std::vector<const HapticStep*> by_inquery_time;  // the same, rebuilds in the query
  std::vector<double> busy_us, prepare_us, inquery_us;
  std::vector<double> in_range_us, deeper_us;
  double inquery_total_us = 0.0;
  std::vector<pd::PenetrationResult::Work> works;
  double build_us = 0.0;
  for (const HapticStep& s : r.steps) {
    ++m.steps;
    if (s.fcl_collide != s.c.colliding) ++m.fcl_disagree;
    if (!s.pd.in_collision) {
      free_us.push_back(s.pd.time_us);
      continue;
    }
    ++m.colliding;
    pd_us.push_back(s.pd.time_us);
    (s.pd.depth <= kHapticTargetMaxDepth ? in_range_us : deeper_us).push_back(s.pd.time_us);
    busy_us.push_back(s.pd.time_us + s.prepare_us);
    prepare_us.push_back(s.prepare_us);
    m.lists_completed += s.lists_completed;
    m.prepare_paused += s.prepare_paused;
    if (s.inquery_in_collision) {
      inquery_us.push_back(s.inquery_time_us);
      (s.list_builds > 0 ? with_build_us : without_build_us).push_back(s.inquery_time_us);
      by_inquery_time.push_back(&s);
      build_us += s.list_build_us;
      inquery_total_us += s.inquery_time_us;
    }
    by_time.push_back(&s);
    works.push_back(s.pd.work);
    fcl_us.push_back(s.fcl_time_us);
    iters.push_back(s.pd.iterations);
    boxes.push_back(s.box_tests);
    tris.push_back(s.triangle_tests);
    m.cold_restarts += s.cold_restart;
    m.cross_checks += s.cross_checked;
    m.not_converged += !s.converged;
    m.invalid += !(s.pd.valid && s.pd.verified_free);
    m.not_free_beyond += !s.free_beyond;
    if (s.has_budget && s.budget_in_collision) {
      m.has_budget = true;
      budget_us.push_back(s.budget_time_us);
      m.budget_not_converged += !s.budget_converged;
      m.budget_not_free += !s.budget_free;
      if (s.has_ref) {
        const double e = RelativeError(s.budget_depth, s.ref.depth);
        if (!std::isnan(e)) budget_err.push_back(std::fabs(e));
      }
    }
    if (s.has_ref) {
      const double e = RelativeError(s.pd.depth, s.ref.depth);
      if (!std::isnan(e)) {
        ++m.n_ref;
        err.push_back(std::fabs(e));
        signed_err.push_back(e);
      }
    }
  }
  m.pd_us = Summarize(pd_us);
  m.in_range_us = Summarize(in_range_us);
  m.deeper_us = Summarize(deeper_us);
  m.pd_free_us = Summarize(free_us);
  m.fcl_us = Summarize(fcl_us);
  m.p999_us = Percentile(pd_us, 99.9);
  m.median_ratio = m.pd_us.median / m.fcl_us.median;
  m.p99_ratio = m.pd_us.p99 / m.fcl_us.p99;
  m.mean_iterations = Mean(iters);
  m.mean_box_tests = Mean(boxes);
  m.mean_triangle_tests = Mean(tris);
  m.with_build_us = Summarize(with_build_us);
  m.without_build_us = Summarize(without_build_us);
  if (inquery_total_us > 0.0) m.build_time_share = build_us / inquery_total_us;
  m.busy_us = Summarize(busy_us);
  m.prepare_us = Summarize(prepare_us);
  m.inquery_us = Summarize(inquery_us);
  // The slowest 1% (at least one query), slowest first.
  std::stable_sort(by_time.begin(), by_time.end(), [](const HapticStep* a, const HapticStep* b) {
    return a->pd.time_us > b->pd.time_us;
  });
  m.slowest_1pct = std::min<int>(static_cast<int>(by_time.size()),
                                 std::max(1, static_cast<int>(by_time.size()) / 100));
  std::vector<pd::PenetrationResult::Work> slowest_works;
  for (int i = 0; i < m.slowest_1pct; ++i) slowest_works.push_back(by_time[i]->pd.work);
  std::stable_sort(by_inquery_time.begin(), by_inquery_time.end(),
                   [](const HapticStep* a, const HapticStep* b) {
                     return a->inquery_time_us > b->inquery_time_us;
                   });
  m.inquery_slowest_1pct = std::min<int>(
      static_cast<int>(by_inquery_time.size()),
      std::max(1, static_cast<int>(by_inquery_time.size()) / 100));
  for (int i = 0; i < m.inquery_slowest_1pct; ++i)
    m.inquery_slowest_1pct_with_build += by_inquery_time[i]->list_builds > 0;
  m.work = SharesOf(works);
  m.slowest_1pct_work = SharesOf(slowest_works);
  m.abs_error = Summarize(err);
  m.budget_us = Summarize(budget_us);
  m.budget_abs_error = Summarize(budget_err);
  m.signed_mean_error = Mean(signed_err);
  return m;
}

HapticPathRun FirstHapticPathRun(const HapticPairResult& r) {
  HapticPathRun p;
  p.path_seed = r.path_seed;
  for (const HapticStep& s : r.steps) {
    if (s.pd.in_collision) {
      p.us.push_back(s.pd.time_us);
      p.cpu_us.push_back(s.cpu_us);
      p.work.push_back(s.box_tests + s.triangle_tests);
      p.depth.push_back(s.pd.depth);
      p.cold_restarts += s.cold_restart;
      p.not_free += !s.free_beyond;
    }
    if (s.has_budget && s.budget_in_collision) {
      p.budget_us.push_back(s.budget_time_us);
      p.budget_cpu_us.push_back(s.budget_cpu_us);
      p.budget_stopped += !s.budget_converged;
      p.budget_not_free += !s.budget_free;
    }
  }
  return p;
}

HapticPathsSummary SummarizeHapticPaths(const HapticPairResult& r, double target_max_us) {
  HapticPathsSummary m;
  double max_all = 0.0, in_range = 0.0, p99 = 0.0, work = 0.0, budget_all = 0.0;
  double cpu_all = 0.0, budget_cpu_all = 0.0;
  bool any_budget = false;
  auto add_path = [&](const HapticPathRun& p) {
    ++m.paths;
    m.colliding += static_cast<int>(p.us.size());
    const Summary t = Summarize(p.us);
    m.max_us.push_back(t.max);
    m.paths_over_target += t.max > target_max_us;
    cpu_all = std::max(cpu_all, Max(p.cpu_us));
    max_all = std::max(max_all, t.max);
    p99 = std::max(p99, t.p99);
    for (size_t i = 0; i < p.us.size(); ++i)
      if (p.depth[i] <= kHapticTargetMaxDepth) in_range = std::max(in_range, p.us[i]);
    for (double w : p.work) work = std::max(work, w);
    m.cold_restarts += p.cold_restarts;
    m.not_free += p.not_free;
    m.budget_stopped += p.budget_stopped;
    m.budget_not_free += p.budget_not_free;
    if (!p.budget_us.empty()) {
      any_budget = true;
      const double b = Summarize(p.budget_us).max;
      m.budget_max_us.push_back(b);
      m.budget_paths_over_target += b > target_max_us;
      budget_all = std::max(budget_all, b);
      const double b_cpu = Max(p.budget_cpu_us);
      m.budget_cpu_max_us.push_back(b_cpu);
      m.budget_cpu_paths_over_target += b_cpu > target_max_us;
      budget_cpu_all = std::max(budget_cpu_all, b_cpu);
    }
  };
  add_path(FirstHapticPathRun(r));
  for (const HapticPathRun& p : r.more_paths) add_path(p);
  m.max_us_all = max_all;
  m.cpu_max_us_all = cpu_all;
  m.in_range_max_us = in_range;
  m.worst_p99_us = p99;
  m.max_work = work;
  if (any_budget) {
    m.budget_max_us_all = budget_all;
    m.budget_cpu_max_us_all = budget_cpu_all;
  }
  return m;
}

}  // namespace pd_bench
