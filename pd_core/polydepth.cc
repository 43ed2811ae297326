#include "pd_core/polydepth.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "pd_core/candidate_pairs.h"
#include "pd_core/contact_constraints.h"
#include "pd_core/contact_regions.h"
#include "pd_core/fibonacci_sphere.h"
#include "pd_core/mesh_collision.h"
#include "pd_core/min_norm_point.h"
#include "pd_core/model_pair.h"
#include "pd_core/support_plane_starts.h"
#include "pd_core/translational_ccd.h"

namespace pd {

const char* InitializerName(Initializer init) {
  switch (init) {
    case Initializer::kNone: return "none";
    case Initializer::kMotionCoherence: return "motion_coherence";
    case Initializer::kMaximallyClear: return "maximally_clear";
    case Initializer::kCentroidDifference: return "centroid_difference";
    case Initializer::kRandom: return "random";
    case Initializer::kSamplingSearch: return "sampling_search";
  }
  return "unknown";
}

namespace {

// A collision-free configuration and where it came from.
struct Start {
  Vector3 q_S;
  Initializer origin;
  double contact_norm = 0.0;  // |q| after the first out-projection
  Vector3 contact_q_S = Vector3::Zero();
};

}  // namespace

namespace {

// Out-projection: from a free q_from toward q_to, the last free point before
// first contact, backed off by `margin` (m) along the motion. Returns q_to if
// the whole segment is free. *touched tells which.
Vector3 OutProject(const ModelPair& pair, const Vector3& q_from, const Vector3& q_to,
                   double margin, bool* touched) {
  const Vector3 d = q_to - q_from;
  const double len = d.norm();
  if (len <= 0.0) {
    *touched = false;
    return q_to;
  }
  const double s = FirstContactAlongTranslation(pair, q_from, d);
  if (s < 0) {
    *touched = false;
    return q_to;
  }
  *touched = true;
  return q_from + std::max(0.0, s - margin / len) * d;
}

}  // namespace

struct PolyDepthSolver::Impl {
  std::vector<ContactConstraint> constraints;
  MinNormScratch qp;
  std::vector<Start> starts;
  std::vector<SupportPlaneStart> support_starts;
  std::mt19937_64 rng;
  CandidatePairs candidates;  // leaf pairs near the last contact (warm start)
  // Warm-start state, relative to the scene (so a moving scene is fine).
  bool has_previous = false;       // previous frame collided and was solved
  bool has_previous_free = false;  // previous frame was collision-free
  Vector3 previous_q_S = Vector3::Zero();
  Vector3 previous_n_S = Vector3::Zero();
  RelativePose previous_X_SP;

  // Where `constraints` were last localised (they are reused for regions).
  Vector3 constraints_q_S = Vector3::Constant(1e300);
  // Best verified-free contact configuration of the current query.
  Vector3 best_q_S = Vector3::Zero();
  double best_norm = 0.0;
  Initializer best_origin = Initializer::kNone;
  int iterations = 0;

  // Iterates localisation, in-projection and out-projection from a contact
  // configuration q_c (free, touching) until |q| stops improving.
  void Iterate(const ModelPair& pair, const PolyDepthOptions& opt, double size, Vector3 q_c,
               Initializer origin) {
  Impl& s = *this;
  const double tol = opt.convergence_tol * size;
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  s.Offer(q_c, origin);
  double norm_c = q_c.norm();
  for (int it = 0; it < opt.max_iterations; ++it) {
    ++s.iterations;
    // Localise the contact space at q_c and in-project toward the query.
    CollectContactConstraints(pair, q_c, contact_distance, &s.constraints);
    s.constraints_q_S = q_c;
    if (s.constraints.empty()) break;
    // Aim strictly inside free space: an exactly touching target is
    // ambiguous under round-off, a target `margin` clear is not.
    for (ContactConstraint& c : s.constraints) c.c += margin;
    const MinNormResult qp = MinNormPoint(s.constraints, tol, &s.qp);
    const Vector3 q_new = qp.q;
    if (q_new.norm() >= norm_c - tol) break;  // q_c is locally optimal
    // Move toward q_new; if it is reachable free, out-project to the query.
    bool touched = false;
    Vector3 q_next = OutProject(pair, q_c, q_new, margin, &touched);
    if (!touched) q_next = OutProject(pair, q_new, Vector3::Zero(), margin, &touched);
    if (!touched) break;  // reached the query free: cannot happen when colliding
    const double norm_next = q_next.norm();
    const bool improved = norm_next < norm_c - tol;
    q_c = q_next;
    norm_c = norm_next;
    s.Offer(q_c, origin);
    if (!improved) break;
  }
}

  void Offer(const Vector3& q_S, Initializer origin) {
    const double n = q_S.norm();
    if (n < best_norm) {
      best_norm = n;
      best_q_S = q_S;
      best_origin = origin;
    }
  }
};

PolyDepthSolver::PolyDepthSolver(std::shared_ptr<const CollisionModel> probe,
                                 std::shared_ptr<const CollisionModel> scene,
                                 PolyDepthOptions options)
    : probe_(std::move(probe)), scene_(std::move(scene)), options_(options),
      impl_(std::make_unique<Impl>()) {
  impl_->rng.seed(options_.seed);
  impl_->constraints.reserve(1024);
  impl_->starts.reserve(64);
  impl_->qp.unique.reserve(1024);
  impl_->qp.lambda.reserve(1024);
}

PolyDepthSolver::~PolyDepthSolver() = default;

void PolyDepthSolver::ResetWarmStart() {
  impl_->candidates.Invalidate();
  impl_->has_previous = false;
  impl_->has_previous_free = false;
}



PenetrationResult PolyDepthSolver::Solve(const Isometry3& X_WP, const Isometry3& X_WS,
                                         bool coherent) {
  const auto t_start = std::chrono::steady_clock::now();
  Impl& s = *impl_;
  PenetrationResult result;
  ModelPair pair(*probe_, *scene_, X_WP, X_WS);
  pair.candidates = &s.candidates;
  const double size = pair.size();
  const double margin = options_.separation_margin * size;
  s.iterations = 0;
  s.constraints_q_S = Vector3::Constant(1e300);

  result.in_collision = InCollision(pair, Vector3::Zero());
  if (!result.in_collision) {
    // Remember this free pose: the next contact starts from it.
    s.has_previous = false;
    s.has_previous_free = true;
    s.previous_X_SP = pair.X_SP;
    result.time_us = std::chrono::duration<double, std::micro>(
                         std::chrono::steady_clock::now() - t_start).count();
    return result;
  }
  s.best_norm = 1e300;
  s.best_origin = Initializer::kNone;

  // 1. Motion coherence: step off the previous answer along its normal by
  // about the motion since then, verify freedom, and iterate from there.
  const bool warm = coherent && options_.warm_start;
  // How far any probe point moved since the previous frame (m).
  const double motion =
      (warm && (s.has_previous || s.has_previous_free))
          ? (pair.X_SP.p_SP - s.previous_X_SP.p_SP).norm() +
                RotationAngleBetween(s.previous_X_SP.R_SP, pair.X_SP.R_SP) * probe_->radius()
          : 0.0;
  // Keep the leaf-pair list around the configuration we restart from, with
  // room for the restart's step-off (about the motion) and the iterations'
  // contact distance; a fast probe gets a wider list instead of a full BVH
  // descent in every query.
  if (warm && (s.has_previous || s.has_previous_free)) {
    const Vector3 center = s.has_previous
                               ? s.previous_q_S
                               : Vector3(s.previous_X_SP.p_SP - pair.X_SP.p_SP);
    const double need = 2.0 * motion + 6.0 * options_.contact_tol * size;
    if (!s.candidates.Covers(pair, center, center, need))
      s.candidates.Build(pair, center, std::max(options_.candidate_radius * size, 1.5 * need));
  }
  if (warm && s.has_previous) {
    double offset = motion + options_.contact_tol * size;
    for (int attempt = 0; attempt < 4; ++attempt, offset *= 4.0) {
      const Vector3 q0 = s.previous_q_S + offset * s.previous_n_S;
      if (InCollision(pair, q0)) continue;
      bool touched = false;
      const Vector3 q_c = OutProject(pair, q0, Vector3::Zero(), margin, &touched);
      if (touched) s.Iterate(pair, options_, size, q_c, Initializer::kMotionCoherence);
      break;
    }
  }

  // 1b. Coming from a free frame: put the probe back where it was then (a
  // free place a short way back along the motion) and out-project from there.
  if (warm && !s.has_previous && s.has_previous_free && s.best_origin == Initializer::kNone) {
    const Vector3 back = s.previous_X_SP.p_SP - pair.X_SP.p_SP;
    const double len = back.norm();
    if (len > 0.0) {
      double offset = options_.contact_tol * size;
      for (int attempt = 0; attempt < 3; ++attempt, offset *= 4.0) {
        const Vector3 q0 = back + offset * (back / len);
        if (InCollision(pair, q0)) continue;
        bool touched = false;
        const Vector3 q_c = OutProject(pair, q0, Vector3::Zero(), margin, &touched);
        if (touched) {
          s.Iterate(pair, options_, size, q_c, Initializer::kMotionCoherence);
        } else {
          // Free all the way: the query only touches (the CCD counts no
          // contact at the very end). Back off along the motion by the
          // margin; without this the cold starts answered from outside the
          // scene's hull, through the wall (tests/pd_core/test_hard_cases.cc).
          const Vector3 q_b = margin * (back / len);
          if (!InCollision(pair, q_b)) s.Iterate(pair, options_, size, q_b, Initializer::kMotionCoherence);
        }
        break;
      }
    }
  }

  // 2. Cold starts (also the fallback when coherence found nothing).
  if (s.best_origin == Initializer::kNone) {
    s.starts.clear();
    ComputeSupportPlaneStarts(pair, &s.support_starts);
    // Maximally clear: the best support-plane separations of the two models.
    for (int i = 0; i < std::min<int>(options_.num_maximally_clear, s.support_starts.size()); ++i)
      s.starts.push_back({s.support_starts[i].q_S, Initializer::kMaximallyClear});
    if (options_.use_centroid) {
      const Vector3 d = pair.X_SP * probe_->centroid() - scene_->centroid();
      if (d.norm() > 1e-9 * size)
        s.starts.push_back({SupportPlaneTranslation(pair, d.normalized()),
                            Initializer::kCentroidDifference});
    }
    std::normal_distribution<double> gauss;
    for (int i = 0; i < options_.num_random; ++i) {
      Vector3 u(gauss(s.rng), gauss(s.rng), gauss(s.rng));
      if (u.norm() < 1e-9) continue;
      s.starts.push_back({SupportPlaneTranslation(pair, u.normalized()), Initializer::kRandom});
    }
    // Out-project every start once, then iterate from the closest few.
    for (Start& st : s.starts) {
      bool touched = false;
      st.contact_q_S = OutProject(pair, st.q_S, Vector3::Zero(), margin, &touched);
      st.contact_norm = touched ? st.contact_q_S.norm() : 1e300;
    }
    std::sort(s.starts.begin(), s.starts.end(),
              [](const Start& a, const Start& b) { return a.contact_norm < b.contact_norm; });
    for (int i = 0; i < std::min<int>(options_.num_iterated_starts, s.starts.size()); ++i) {
      if (s.starts[i].contact_norm >= 1e300) break;
      s.Iterate(pair, options_, size, s.starts[i].contact_q_S, s.starts[i].origin);
    }
  }

  // 3. Verify; fall back to a dense directional search if needed.
  bool valid = s.best_origin != Initializer::kNone && !InCollision(pair, s.best_q_S);
  if (!valid && options_.num_sampling_directions > 0) {
    s.best_norm = 1e300;
    s.best_origin = Initializer::kNone;
    Vector3 best_contact = Vector3::Zero();
    double best_norm = 1e300;
    const int n = options_.num_sampling_directions;
    for (int i = 0; i < n; ++i) {
      const Vector3 u = FibonacciDirection(i, n);
      bool touched = false;
      const Vector3 q_c =
          OutProject(pair, SupportPlaneTranslation(pair, u), Vector3::Zero(), margin, &touched);
      if (touched && q_c.norm() < best_norm) best_norm = q_c.norm(), best_contact = q_c;
    }
    if (best_norm < 1e300)
      s.Iterate(pair, options_, size, best_contact, Initializer::kSamplingSearch);
    valid = s.best_origin != Initializer::kNone && !InCollision(pair, s.best_q_S);
  }

  result.valid = valid;
  result.iterations = s.iterations;
  result.initializer = s.best_origin;
  if (s.best_origin != Initializer::kNone) {
    const Matrix3 R_WS = X_WS.linear();
    result.translation_W = R_WS * s.best_q_S;
    result.depth = s.best_norm;
    result.normal_W = s.best_norm > 0 ? Vector3(result.translation_W / s.best_norm)
                                      : Vector3::Zero();
    if (s.constraints_q_S != s.best_q_S)
      CollectContactConstraints(pair, s.best_q_S, options_.contact_tol * size, &s.constraints);
    result.num_contacts = static_cast<int>(s.constraints.size());
    GroupContactRegions(s.constraints, s.best_q_S, X_WS, 0.1 * size, &result);
  }
  s.has_previous_free = false;
  if (valid) {
    s.has_previous = true;
    s.previous_q_S = s.best_q_S;
    s.previous_n_S = s.best_q_S / std::max(s.best_norm, 1e-300);
    s.previous_X_SP = pair.X_SP;
  } else {
    s.has_previous = false;
  }
  result.time_us = std::chrono::duration<double, std::micro>(
                       std::chrono::steady_clock::now() - t_start).count();
  return result;
}

}  // namespace pd
