// haptic_work: the haptic paths of bench_pd (haptic_paths.h) solved warm by
// PolyDepth alone, reporting the work per colliding query (box + triangle
// tests: deterministic, unlike time on a shared machine) and optionally
// dumping every answer's depth, so a solver change can be A/B-checked in
// seconds for cost and for bit-identical answers. Timing, FCL and accuracy
// are bench_pd's job.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/cases/bench_models.h"
#include "bench/cases/haptic_paths.h"
#include "bench/cases/scenarios.h"
#include "bench/common/stats.h"
#include "bench/report/bench_results.h"
#include "bench/report/summaries.h"
#include "bench/runs/answer_free.h"
#include "pd_core/geometry/fibonacci_sphere.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

int main(int argc, char** argv) {
  using namespace pd_bench;
  CLI::App app{"Work per warm PolyDepth query on bench_pd's haptic paths"};
  std::string mesh_dir = std::string(PD_SOURCE_DIR) + "/build/meshes";
  std::string dump;
  std::vector<std::string> only;
  int steps = 3000;
  uint64_t seed = kDefaultBenchSeed;  // bench_pd's: the same paths
  pd::PolyDepthOptions options;
  int repeat = 0;
  app.add_option("--mesh-dir", mesh_dir, "directory of the .off meshes");
  app.add_option("--dump", dump, "write 'pair index depth_m work iterations list_builds cross_checked' and the work by kind (collision localisation out_projection list_builds other), then time_us and converged, per pose to this file");
  app.add_option("--pairs", only, "only these haptic pairs");
  app.add_option("--steps", steps, "poses per path (1 ms apart)");
  app.add_option("--seed", seed, "path seed (bench_pd's --seed)");
  app.add_option("--candidate-radius", options.candidate_radius,
                 "PolyDepthOptions::candidate_radius (fraction of size) for an A/B");
  app.add_option("--repeat", repeat,
                 "solve each path this many more times, fresh solver each time, unreported (profiling: the solves outweigh the path set-up)");
  app.add_option("--max-work", options.max_work,
                 "PolyDepthOptions::max_work (box + triangle tests; 0 = unbounded)");
  app.add_option("--max-time-us", options.max_time_us,
                 "PolyDepthOptions::max_time_us (us; 0 = unbounded; makes the work load-dependent)");
  app.add_option("--creep-join-iterations", options.creep_join_iterations,
                 "PolyDepthOptions::creep_join_iterations for an A/B (0 = off)");
  bool dump_poses = false;
  app.add_flag("--dump-poses", dump_poses,
               "with --dump: also each pose's X_WP (x y z in m, then qw qx qy qz) for test fixtures");
  bool check_free = false;
  app.add_flag("--check-free", check_free,
               "check every colliding answer free, and free kHapticFreeMargin x size beyond along itself (bench_pd's test); list those that are not");
  int path_depth_every = 0;
  app.add_option("--check-path-depth", path_depth_every,
                 "check the path itself, every this many colliding poses: some translation no longer than twice the path's depth plus 2 mm (one of 256 directions) frees the tool (collision tests only, not the solver); list the poses where none does and exit 1");
  app.add_flag("--defer", options.defer_list_builds,
               "PolyDepthOptions::defer_list_builds: list builds run in PrepareNext after each answer (to the end); their work is reported apart");
  CLI11_PARSE(app, argc, argv);

  std::ofstream out;
  if (!dump.empty()) {
    out.open(dump);
    if (!out) {
      std::cerr << "haptic_work: cannot write " << dump << "\n";
      return 1;
    }
    out.precision(17);
  }
  ModelCache cache(mesh_dir, 1);
  if (path_depth_every == 0)
    std::printf("%-18s %6s %8s %8s %8s %8s %7s %8s %8s %6s  %s\n", "pair", "coll", "work_p50",
                "work_p99", "work_max", "us_p50", "us_p99", "us_max", "builds", "cold",
                "work share: collision/localisation/out-projection/list builds/other %");
  for (const HapticPairSpec& spec : DefaultHapticPairs()) {
    if (!only.empty() && std::find(only.begin(), only.end(), spec.name) == only.end()) continue;
    std::string why;
    auto tool = cache.Get(spec.tool, &why, kHapticToolRadius);
    auto object = tool ? cache.Get(spec.object, &why, kHapticObjectRadius) : nullptr;
    if (!tool || !object) {
      std::cerr << "haptic_work: " << spec.name << ": " << why << "\n";
      return 1;
    }
    const BenchPair pair{spec.name, tool, object};
    const HapticPath path = MakeHapticPath(pair, spec, steps, HapticPathSeed(seed));
    const pd::Isometry3 X_WS = ScenePose(pair);
    double repeat_us = 0.0;
    for (int k = 0; k < repeat; ++k) {
      pd::PolyDepthSolver again(tool->model, object->model, options);
      for (const Case& c : path.cases) {
        repeat_us += again.Solve(c.X_WP, X_WS, /*coherent=*/true).time_us;
        repeat_us += again.PrepareNext().time_us;
      }
    }
    if (repeat > 0)
      std::fprintf(stderr, "%s: %d repeats, PolyDepth %.3f s\n", spec.name.c_str(), repeat,
                   repeat_us * 1e-6);
    if (path_depth_every > 0) {
      // The paths promise a tool kept about spec.depth_m inside the surface
      // (haptic_paths.h): a pose deeper than this bound is one the path
      // generator was not meant to make (before the overhang rule, knot1_bunny
      // on seed 20240611 climbed 13 mm into the bunny's ear from below).
      const double reach = 2.0 * spec.depth_m + 2e-3;
      constexpr int kDirections = 256;
      int checked = 0, too_deep = 0, colliding = 0;
      for (const Case& c : path.cases) {
        if (!c.colliding || colliding++ % path_depth_every != 0) continue;
        ++checked;
        const pd::ModelPair mp(*tool->model, *object->model, c.X_WP, X_WS);
        bool freed = false;
        for (int k = 0; k < kDirections && !freed; ++k)
          freed = !pd::InCollision(mp, reach * pd::FibonacciDirection(k, kDirections));
        if (!freed) {
          ++too_deep;
          std::fprintf(stderr, "%s %d: no translation of %.2f mm frees the tool\n",
                       spec.name.c_str(), c.index, reach * 1e3);
        }
      }
      std::printf("%s: path depth checked at %d colliding poses, %d deeper than %.2f mm\n",
                  spec.name.c_str(), checked, too_deep, reach * 1e3);
      if (too_deep > 0) return 1;
      continue;
    }
    pd::PolyDepthSolver solver(tool->model, object->model, options);
    std::vector<double> work, us, deferred;
    int builds = 0, cold = 0, index = 0, not_free = 0;
    std::vector<pd::PenetrationResult::Work> works;
    bool seen = false;
    for (const Case& c : path.cases) {
      const pd::PenetrationResult r = solver.Solve(c.X_WP, X_WS, /*coherent=*/true);
      const pd::PolyDepthSolver::Preparation prep = solver.PrepareNext();
      if (prep.lists_completed > 0) deferred.push_back(static_cast<double>(prep.box_tests));
      builds += prep.lists_completed;
      if (r.in_collision) {
        work.push_back(static_cast<double>(r.box_tests + r.triangle_tests));
        us.push_back(r.time_us);
        builds += r.list_builds;
        works.push_back(r.work);
        cold += seen && r.warm_start_failed;
        if (check_free) {
          const pd::ModelPair mp(*tool->model, *object->model, c.X_WP, X_WS);
          const pd::Vector3 q_S = X_WS.linear().transpose() * r.translation_W;
          const bool at = !pd::InCollision(mp, q_S);
          const bool beyond = FreeFurtherAlong(mp, q_S);
          if (!(r.valid && at && beyond)) {
            ++not_free;
            std::fprintf(stderr, "%s %d: answer not free (valid %d, free at it %d, beyond %d, depth %.9g, converged %d)\n",
                         spec.name.c_str(), index, r.valid, at, beyond, r.depth, r.converged);
          }
        }
      }
      seen = true;
      if (out)
        out << spec.name << ' ' << index << ' ' << r.depth << ' '
            << r.box_tests + r.triangle_tests << ' ' << r.iterations << ' ' << r.list_builds
            << ' ' << r.cross_checked << ' ' << r.work.collision << ' ' << r.work.localisation
            << ' ' << r.work.out_projection << ' ' << r.work.list_builds << ' ' << r.work.other
            << ' ' << r.time_us << ' ' << r.converged;
      if (out && dump_poses) {
        const pd::Quaternion q(c.X_WP.linear());
        const pd::Vector3 p = c.X_WP.translation();
        out << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << q.w() << ' ' << q.x() << ' '
            << q.y() << ' ' << q.z();
      }
      if (out) out << '\n';
      ++index;
    }
    if (check_free)
      std::fprintf(stderr, "%s: %d answers not free (+%g x size)\n", spec.name.c_str(), not_free,
                   kHapticFreeMargin);
    const WorkShares shares = SharesOf(works);
    if (!deferred.empty())
      std::fprintf(stderr, "%s: %zu deferred list builds (PrepareNext), work p50 %.0f p99 %.0f max %.0f\n",
                   spec.name.c_str(), deferred.size(), Percentile(deferred, 50),
                   Percentile(deferred, 99), Max(deferred));
    std::printf("%-18s %6zu %8.0f %8.0f %8.0f %8.1f %7.1f %8.1f %8d %6d  %.0f/%.0f/%.0f/%.0f/%.0f\n",
                spec.name.c_str(), work.size(), Percentile(work, 50), Percentile(work, 99),
                Max(work), Percentile(us, 50), Percentile(us, 99), Max(us), builds, cold,
                100.0 * shares.collision, 100.0 * shares.localisation,
                100.0 * shares.out_projection, 100.0 * shares.list_builds, 100.0 * shares.other);
  }
  return 0;
}
