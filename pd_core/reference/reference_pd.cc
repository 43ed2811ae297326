#include "pd_core/reference/reference_pd.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "pd_core/reference/directional_exit.h"
#include "pd_core/reference/exact_surface_intersection.h"
#include "pd_core/reference/placed_pair.h"
#include "pd_core/reference/ray_parity_containment.h"

namespace pd {

using reference::Complete;
using reference::Contained;
using reference::DirectionalExit;
using reference::DirectionalScratch;
using reference::Exit;
using reference::kInf;
using reference::MakePair;
using reference::PairGeometry;

namespace {

// The directions of the search: a Fibonacci sphere.
std::vector<Vector3> FibonacciSphere(int n) {
  std::vector<Vector3> dirs;
  dirs.reserve(std::max(n, 0));
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * i;
    dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return dirs;
}

}  // namespace

double DirectionalPenetration(const TriangleMesh& probe, const Isometry3& X_WP,
                              bool probe_closed, const TriangleMesh& scene,
                              const Isometry3& X_WS, bool scene_closed, const Vector3& u_W,
                              double slit_tol_abs) {
  const double norm = u_W.norm();
  if (!(norm > 0.0)) return 0.0;
  const PairGeometry g = MakePair(probe, X_WP, probe_closed, scene, X_WS, scene_closed);
  DirectionalScratch scratch;
  return DirectionalExit(g, u_W / norm, slit_tol_abs, false, kInf, &scratch).distance;
}

// A contact plane of the C-obstacle seen by one directional exit: P moved
// by t touches there, locally free where n·t >= c (n unit, c > 0).
struct ExitPlane {
  Vector3 n;
  double c;
};

// The shortest t with n_k·t >= c_k for every plane (a handful): the best
// over the active sets of one, two or three planes whose point is feasible.
// False when none is (contradictory planes).
bool ShortestInPlanes(const std::vector<ExitPlane>& planes, Vector3* t) {
  const int m = static_cast<int>(planes.size());
  double best = kInf;
  auto consider = [&](const Vector3& x) {
    if (!x.allFinite() || x.norm() >= best) return;
    for (const ExitPlane& p : planes)
      if (p.n.dot(x) < p.c * (1.0 - 1e-9)) return;
    best = x.norm();
    *t = x;
  };
  for (int a = 0; a < m; ++a) {
    consider(planes[a].c * planes[a].n);
    for (int b = a + 1; b < m; ++b) {
      const Vector3 &na = planes[a].n, &nb = planes[b].n;
      const double k = na.dot(nb), det = 1.0 - k * k;
      if (det > 1e-12)
        consider(((planes[a].c - k * planes[b].c) / det) * na +
                 ((planes[b].c - k * planes[a].c) / det) * nb);
      for (int c = b + 1; c < m; ++c) {
        Matrix3 A;
        A.row(0) = na.transpose();
        A.row(1) = nb.transpose();
        A.row(2) = planes[c].n.transpose();
        if (std::abs(A.determinant()) < 1e-9) continue;
        consider(A.inverse() * Vector3(planes[a].c, planes[b].c, planes[c].c));
      }
    }
  }
  return best < kInf;
}

ReferencePdResult ReferencePenetrationDepth(const TriangleMesh& probe, const Isometry3& X_WP,
                                            bool probe_closed, const TriangleMesh& scene,
                                            const Isometry3& X_WS, bool scene_closed,
                                            const ReferencePdOptions& options) {
  ReferencePdResult result;
  const PairGeometry g = MakePair(probe, X_WP, probe_closed, scene, X_WS, scene_closed);
  const double slit_tol_abs = options.slit_tol * g.size;
  DirectionalScratch scratch;

  std::vector<Vector3> dirs = FibonacciSphere(options.num_directions);
  for (const Vector3& d : options.extra_directions_W) {
    if (d.norm() > 0.0) dirs.push_back(d.normalized());
  }
  if (dirs.empty()) dirs.push_back(Vector3::UnitZ());

  const Exit first = DirectionalExit(g, dirs[0], slit_tol_abs, false, kInf, &scratch);
  result.directions_evaluated = 1;
  if (!first.colliding) return result;
  result.in_collision = true;

  // Exits at or beyond `cutoff` come back as infinity, which saves the pairs
  // that only touch beyond it.
  auto evaluate = [&](const Vector3& u, double cutoff) {
    ++result.directions_evaluated;
    return DirectionalExit(g, u, slit_tol_abs, true, cutoff, &scratch);
  };
  // Sphere sweep: exits up to kStartSlack times the best so far are kept
  // exactly, as candidate starts for the refinement.
  constexpr double kStartSlack = 1.5;
  // Refinement evaluations see exits up to this many times the current best
  // (so a worse exit still reports its contact plane to the model).
  constexpr double kModelSlack = 1.5;
  std::vector<std::pair<double, int>> scored;
  std::vector<Vector3> normals(dirs.size(), Vector3::Zero());
  scored.reserve(dirs.size());
  scored.emplace_back(first.distance, 0);
  normals[0] = first.normal_W;
  double best = first.distance;
  for (int i = 1; i < static_cast<int>(dirs.size()); ++i) {
    const Exit e = evaluate(dirs[i], kStartSlack * best);
    best = std::min(best, e.distance);
    scored.emplace_back(e.distance, i);
    normals[i] = e.normal_W;
  }
  std::sort(scored.begin(), scored.end());
  Vector3 best_u = dirs[scored[0].second];

  // Refine from the best directions that are not neighbours of one another.
  const double spacing = std::sqrt(4.0 * M_PI / std::max(options.num_directions, 1));
  const double min_separation_cos = std::cos(std::min(2.0 * spacing, M_PI));
  std::vector<std::pair<double, int>> starts;
  for (const auto& [value, i] : scored) {
    if (static_cast<int>(starts.size()) >= options.num_refine_starts || value == kInf) break;
    bool distinct = true;
    for (const auto& start : starts) {
      distinct &= dirs[start.second].dot(dirs[i]) < min_separation_cos;
    }
    if (distinct) starts.emplace_back(value, i);
  }
  // Planes a refinement keeps from its exits near the current best.
  constexpr size_t kModelPlanes = 5;
  // A pattern step below this angle (rad) moves an exit by under 1e-7 of
  // its length: the start has converged.
  constexpr double kFinestStep = 1e-7;
  std::vector<ExitPlane> model;
  for (const auto& [start_value, start] : starts) {
    // Jump to the contact normal at the exit (for a single planar contact
    // that is the local optimum); else an opportunistic pattern search on
    // the sphere with a shrinking angular step, whose worse exits lend their
    // contact planes to a local model: at an optimum where two or three
    // contacts meet (a crease or corner of the C-obstacle) the pattern's
    // fixed axes zig-zag, the model's shortest point lands there.
    Vector3 u = dirs[start], n = normals[start];
    double f = start_value;
    model.clear();
    auto learn = [&](const Exit& e, const Vector3& v) {
      if (!(e.distance < kInf) || e.normal_W.squaredNorm() == 0.0) return;
      const ExitPlane p{e.normal_W, e.normal_W.dot(e.distance * v)};
      if (!(p.c > 0.0)) return;
      for (const ExitPlane& q : model)
        if (q.n.dot(p.n) > 1.0 - 1e-12 && std::abs(q.c - p.c) <= 1e-12 * g.size) return;
      if (model.size() >= kModelPlanes) model.erase(model.begin());
      model.push_back(p);
    };
    if (n.squaredNorm() > 0.0) learn(Exit{true, f, n}, u);
    auto normal_is_new = [&]() { return n.squaredNorm() > 0.0 && u.dot(n) < 1.0 - 1e-15; };
    bool try_normal = normal_is_new();
    double step = spacing;
    int evals = 0;
    // One evaluation along v: a shorter exit becomes the current one (its
    // normal is tried next), a longer one lends its plane to the model.
    auto try_direction = [&](const Vector3& v) {
      const Exit e = evaluate(v, kModelSlack * f);
      ++evals;
      if (!(e.distance < f)) {
        learn(e, v);
        return false;
      }
      u = v;
      f = e.distance;
      n = e.normal_W;
      learn(e, v);
      try_normal = normal_is_new();
      return true;
    };
    while (evals < options.refine_iterations && step > kFinestStep) {
      if (try_normal) {
        try_normal = false;
        try_direction(n);
        continue;
      }
      Vector3 e1, e2;
      Complete(u, &e1, &e2);
      const Vector3 moves[4] = {e1, e2, -e1, -e2};
      bool improved = false;
      for (const Vector3& m : moves) {
        if (evals >= options.refine_iterations) break;
        if ((improved = try_direction((std::cos(step) * u + std::sin(step) * m).normalized())))
          break;
      }
      // No pattern move gained: the model's shortest point, once, before
      // the step shrinks.
      Vector3 t_model;
      if (!improved && evals < options.refine_iterations && model.size() >= 2 &&
          ShortestInPlanes(model, &t_model) && t_model.normalized().dot(u) < 1.0 - 1e-15)
        improved = try_direction(t_model.normalized());
      if (!improved) step *= 0.5;
    }
    if (f < best) {
      best = f;
      best_u = u;
    }
  }
  result.depth = best;
  result.direction_W = best_u;
  result.translation_W = best * best_u;
  return result;
}

bool ReferenceInCollision(const TriangleMesh& probe, const Isometry3& X_WP, bool probe_closed,
                          const TriangleMesh& scene, const Isometry3& X_WS, bool scene_closed,
                          const Vector3& t_W) {
  const PairGeometry g =
      MakePair(probe, TranslatedPose(X_WP, t_W), probe_closed, scene, X_WS, scene_closed);
  return reference::SurfacesIntersect(g) || Contained(g, Vector3::Zero());
}

}  // namespace pd

