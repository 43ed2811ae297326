#include "bench/runs/reference_runner.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

namespace pd_bench {
namespace {

// Fraction of the pair size (sum of radii) added to the reference answer
// before checking it is free.
constexpr double kRefCheckBackoff = 1e-6;

}  // namespace

std::vector<int> SpreadIndices(int n, int k) {
  std::vector<int> idx;
  if (n <= 0 || k <= 0) return idx;
  if (k >= n) k = n;
  for (int i = 0; i < k; ++i) idx.push_back(static_cast<int>((i + 0.5) * n / k));
  return idx;
}

void RunReference(const BenchPair& pair, const std::vector<RefJob>& jobs,
                  const pd::ReferencePdOptions& options, int threads, Progress* progress) {
  const pd::TriangleMesh& P = pair.probe->model->mesh();
  const pd::TriangleMesh& S = pair.scene->model->mesh();
  const bool p_closed = pair.probe->closed, s_closed = pair.scene->closed;
  const pd::Isometry3 X_WS = ScenePose(pair);
  std::atomic<size_t> next{0};
  std::mutex progress_mutex;
  auto worker = [&] {
    for (size_t i; (i = next++) < jobs.size();) {
      const RefJob& job = jobs[i];
      const auto t0 = std::chrono::steady_clock::now();
      const pd::ReferencePdResult r =
          pd::ReferencePenetrationDepth(P, job.c->X_WP, p_closed, S, X_WS, s_closed, options);
      job.out->time_ms = std::chrono::duration<double, std::milli>(
                             std::chrono::steady_clock::now() - t0).count();
      job.out->depth = r.in_collision ? r.depth : 0.0;
      job.out->directions = r.directions_evaluated;
      // The reference stops exactly at touching contact (closed triangles
      // still intersect there): check a hair further out.
      const pd::ModelPair mp(*pair.probe->model, *pair.scene->model, job.c->X_WP, X_WS);
      const pd::Vector3 t_W = r.translation_W + kRefCheckBackoff * mp.size() * r.direction_W;
      job.out->ref_answer_free = !pd::InCollision(mp, X_WS.linear().transpose() * t_W);
      job.out->pd_answer_free = !pd::ReferenceInCollision(P, job.c->X_WP, p_closed, S, X_WS,
                                                          s_closed, job.pd_translation_W);
      std::lock_guard<std::mutex> lock(progress_mutex);
      if (progress) progress->Tick();
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

void RunReference(const BenchPair& pair, const std::vector<RefJob>& jobs, const RunSettings& st,
                  Progress* progress, bool haptic) {
  pd::ReferencePdOptions options;
  options.num_directions = haptic ? st.haptic_ref_directions : st.ref_directions;
  options.refine_iterations = haptic ? st.haptic_ref_refine_iterations : st.ref_refine_iterations;
  options.num_refine_starts = st.ref_refine_starts;
  RunReference(pair, jobs, options, st.ref_threads, progress);
}

}  // namespace pd_bench
