#include "pd_core/pair_pd_solver.h"

#include <chrono>
#include <stdexcept>

#include "pd_core/convex/closed_form_pd.h"
#include "pd_core/convex/convex_pd.h"
#include "pd_core/convex/minkowski_difference.h"
#include "pd_core/geometry/tessellate_geometry.h"

namespace pd {

const char* PdMethodName(PdMethod method) {
  switch (method) {
    case PdMethod::kClosedForm: return "closed_form";
    case PdMethod::kConvexGjkEpa: return "convex_gjk_epa";
    case PdMethod::kPolyDepth: return "polydepth";
  }
  return "unknown";
}

PdMethod ChoosePdMethod(const Geometry& probe, const Geometry& scene) {
  if (!probe.bounded())
    throw std::invalid_argument("PD probe must be bounded; got a " + probe.Describe() + " probe");
  if (HasClosedFormPd(probe.kind(), scene.kind())) return PdMethod::kClosedForm;
  if (!probe.convex() || !scene.convex()) return PdMethod::kPolyDepth;
  return PdMethod::kConvexGjkEpa;
}

struct PairPdSolver::Impl {
  std::unique_ptr<PolyDepthSolver> polydepth;  // kPolyDepth only
  ConvexPdOptions convex_options;
  EpaScratch epa;
  Vector3 previous_n_W = Vector3::Zero();  // warm start of GJK
};

PairPdSolver::PairPdSolver(std::shared_ptr<const Geometry> probe,
                           std::shared_ptr<const Geometry> scene, PolyDepthOptions options)
    : probe_(std::move(probe)), scene_(std::move(scene)), options_(options),
      impl_(std::make_unique<Impl>()) {
  if (!probe_ || !scene_) throw std::invalid_argument("PairPdSolver: null geometry");
  method_ = ChoosePdMethod(*probe_, *scene_);
  if (method_ == PdMethod::kPolyDepth) {
    auto model_of = [](const Geometry& g) {
      return g.model() ? g.model()
                       : CollisionModel::Build(TessellateGeometry(g, kTessellationChordError));
    };
    impl_->polydepth =
        std::make_unique<PolyDepthSolver>(model_of(*probe_), model_of(*scene_), options_);
  }
  // Reserve EPA scratch so the servo loop does not allocate.
  impl_->epa.vertices.reserve(4 + 2 * impl_->convex_options.max_epa_iterations);
  impl_->epa.faces.reserve(4096);
  impl_->epa.stack.reserve(256);
  impl_->epa.horizon.reserve(128);
}

PairPdSolver::~PairPdSolver() = default;

PenetrationResult PairPdSolver::Solve(const Isometry3& X_WP, const Isometry3& X_WS, bool coherent) {
  if (method_ == PdMethod::kPolyDepth) return impl_->polydepth->Solve(X_WP, X_WS, coherent);
  const auto t0 = std::chrono::steady_clock::now();
  const Geometry& P = *probe_;
  const Geometry& S = *scene_;
  PairPdAnswer answer;
  if (method_ == PdMethod::kClosedForm) {
    answer = ClosedFormPenetrationDepth(P, X_WP, S, X_WS);
  } else {
    const Vector3 guess = coherent && options_.warm_start ? impl_->previous_n_W : Vector3::Zero();
    answer = ConvexPenetrationDepth(P, X_WP, S, X_WS, impl_->convex_options, guess, &impl_->epa);
    if (!answer.converged) ++epa_fallbacks_;
  }
  PenetrationResult r;
  r.iterations = answer.iterations;
  if (answer.in_collision) {
    const double size = P.radius() + (S.bounded() ? S.radius() : P.radius());
    const Vector3& n = answer.normal_W;
    r.in_collision = true;
    r.translation_W = (answer.depth + options_.separation_margin * size) * n;
    r.depth = r.translation_W.norm();
    r.normal_W = n;
    // Separation certificate at the answer: a plane with normal n between
    // the scene and the moved probe.
    const Vector3 p_W = X_WP * P.Support(X_WP.linear().transpose() * (-n));
    double overlap;
    if (!S.bounded()) {
      overlap = n.dot(X_WS.translation()) - n.dot(p_W + r.translation_W);
    } else {
      overlap = MinkowskiDifference{&P, &S, X_WP, X_WS}.FullSupportValue(n) - n.dot(r.translation_W);
    }
    r.valid = overlap < 0.0 && std::isfinite(r.depth);
    ContactRegion& region = r.regions[0];
    region.p_W = p_W;
    region.n_W = n;
    region.local_depth = r.depth;
    region.num_features = 1;
    r.num_regions = 1;
    r.num_contacts = 1;
    impl_->previous_n_W = n;
  }
  r.time_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

bool PairPdSolver::PrepareNext(const std::function<bool()>& pause) {
  return impl_->polydepth ? impl_->polydepth->PrepareNext(pause).done : true;
}

void PairPdSolver::ResetWarmStart() {
  if (impl_->polydepth) impl_->polydepth->ResetWarmStart();
  impl_->previous_n_W = Vector3::Zero();
}

}  // namespace pd
