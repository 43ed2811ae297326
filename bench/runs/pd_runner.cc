#include "bench/runs/pd_runner.h"

#include "bench/runs/answer_free.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

namespace pd_bench {
namespace {

PdOutcome Check(const BenchPair& pair, const Case& c, const pd::Isometry3& X_WS,
                const pd::PenetrationResult& r) {
  PdOutcome o;
  o.in_collision = r.in_collision;
  o.valid = r.valid;
  o.depth = r.depth;
  o.time_us = r.time_us;
  o.iterations = r.iterations;
  o.starts = r.starts;
  o.iterated_starts = r.iterated_starts;
  o.box_tests = static_cast<double>(r.box_tests);
  o.triangle_tests = static_cast<double>(r.triangle_tests);
  o.work = r.work;
  o.contacts = r.num_contacts;
  o.initializer = pd::InitializerName(r.initializer);
  o.translation_W = r.translation_W;
  // ModelPair queries take the probe offset in the scene frame S.
  const pd::ModelPair mp(*pair.probe->model, *pair.scene->model, c.X_WP, X_WS);
  const pd::Vector3 offset_S = X_WS.linear().transpose() * r.translation_W;
  o.verified_free = !pd::InCollision(mp, offset_S);
  o.free_beyond = o.verified_free && FreeFurtherAlong(mp, offset_S);
  o.in_pocket = o.verified_free && r.depth > 0 &&
                pd::InCollision(mp, (1.0 + kPocketProbe) * offset_S);
  return o;
}

}  // namespace

std::vector<PdOutcome> RunPolyDepth(const BenchPair& pair, const std::vector<Case>& cases,
                                    const pd::PolyDepthOptions& options, bool coherent,
                                    Progress* progress) {
  const pd::Isometry3 X_WS = ScenePose(pair);
  std::vector<PdOutcome> out;
  out.reserve(cases.size());
  std::unique_ptr<pd::PolyDepthSolver> solver;
  for (const Case& c : cases) {
    if (!solver || !coherent)
      solver = std::make_unique<pd::PolyDepthSolver>(pair.probe->model, pair.scene->model, options);
    const pd::PenetrationResult r = solver->Solve(c.X_WP, X_WS, coherent);
    out.push_back(Check(pair, c, X_WS, r));
    if (progress) progress->Tick();
  }
  return out;
}

std::vector<PdOutcome> RunHeldPolyDepth(const BenchPair& pair, const std::vector<Case>& cases,
                                        const pd::PolyDepthOptions& options, int held_queries,
                                        Progress* progress) {
  const pd::Isometry3 X_WS = ScenePose(pair);
  std::vector<PdOutcome> out;
  out.reserve(cases.size());
  for (const Case& c : cases) {
    pd::PolyDepthSolver solver(pair.probe->model, pair.scene->model, options);
    pd::PenetrationResult r = solver.Solve(c.X_WP, X_WS);
    double time_us = r.time_us, box_tests = r.box_tests, triangle_tests = r.triangle_tests;
    for (int k = 0; k < held_queries; ++k) {
      r = solver.Solve(c.X_WP, X_WS, true);
      time_us += r.time_us;
      box_tests += r.box_tests;
      triangle_tests += r.triangle_tests;
    }
    PdOutcome o = Check(pair, c, X_WS, r);
    o.time_us = time_us;
    o.box_tests = box_tests;
    o.triangle_tests = triangle_tests;
    out.push_back(o);
    if (progress) progress->Tick();
  }
  return out;
}

}  // namespace pd_bench
