#include "haptics/contact/contact_geometry.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace haptics {
namespace {

// Weight of the region's own point among its pressure points, per metre of
// its local depth: small, so that pressure points dominate when there are any.
constexpr double kRegionPointWeight = 0.01;
// At most this many containment tests per mesh object and query (the deepest
// candidates), which bounds the cost for large flat contacts. Primitives
// answer containment in closed form and are not capped.
constexpr int kMaxMeshContainmentTests = 48;

}  // namespace

ContactGeometry::ContactGeometry(std::shared_ptr<const pd::Geometry> tool, const Isometry3& X_TG,
                                 std::vector<SceneObject> objects, const ContactConfig& params,
                                 pd::PolyDepthOptions options)
    : tool_(std::move(tool)),
      X_TG_(X_TG),
      objects_(std::move(objects)),
      params_(params),
      broad_phase_(objects_) {
  if (!tool_) throw std::invalid_argument("PenaltyContact: no tool geometry");
  if (!tool_->bounded()) throw std::invalid_argument("PenaltyContact: the tool must be bounded");
  for (const SceneObject& object : objects_)
    solvers_.push_back(std::make_unique<pd::PairPdSolver>(tool_, object.geometry, options));
  results_.resize(objects_.size());
  candidates_now_.reserve(objects_.size());
  candidates_prev_.reserve(objects_.size());
  candidate_call_.assign(objects_.size(), -1);
  const double same_point_tol = 1e-9 * tool_->radius();
  same_point_tol2_ = same_point_tol * same_point_tol;
  const size_t np = tool_->surface_points().size();
  p_WV_.resize(np);
  depth_points_.reserve(np);
  inside_.reserve(np);
}

bool ContactGeometry::any_polydepth() const {
  for (const auto& solver : solvers_)
    if (solver->method() == pd::PdMethod::kPolyDepth) return true;
  return false;
}

bool ContactGeometry::PrepareNext(const std::function<bool()>& pause) {
  for (int i : candidates_now_)
    if (!solvers_[i]->PrepareNext(pause)) return false;
  return true;
}

void ContactGeometry::ResetWarmStarts() {
  for (auto& solver : solvers_) solver->ResetWarmStart();
  have_previous_ = false;
}

void ContactGeometry::Query(const Isometry3& X_WT, int64_t request_tick, ContactSnapshot* out) {
  const auto t_start = std::chrono::steady_clock::now();
  ++call_;
  out->request_tick = request_tick;
  out->X_WT0 = X_WT;
  out->num_pairs = 0;
  const Isometry3 X_WG = X_WT * X_TG_;
  X_WG_ = X_WG;

  // Broad phase over the tool's motion since the previous call.
  const WorldBox box_W = BoundingBoxInWorld(*tool_, X_WG);
  const WorldBox swept_W = (have_previous_ ? box_W.Joined(previous_box_W_) : box_W).Grown(params_.cull_margin);
  previous_box_W_ = box_W;
  have_previous_ = true;
  candidates_prev_.swap(candidates_now_);
  broad_phase_.Query(swept_W, &candidates_now_);
  for (int i : candidates_now_) candidate_call_[i] = call_;
  for (int i : candidates_prev_) {
    if (candidate_call_[i] == call_) continue;
    // Out of reach again: the next contact starts cold.
    solvers_[i]->ResetWarmStart();
    results_[i] = pd::PenetrationResult{};
  }
  out->num_candidates = static_cast<int>(candidates_now_.size());
  out->num_culled = num_objects() - out->num_candidates;

  for (int i : candidates_now_) {
    const SceneObject& object = objects_[i];
    ++query_count_;
    results_[i] = solvers_[i]->Solve(X_WG, object.X_WS, /*coherent=*/true);
    const pd::PenetrationResult& r = results_[i];
    PairContactModel& m = out->pairs[out->num_pairs++];
    m.object = i;
    m.X_WT0 = X_WT;
    m.num_regions = 0;
    m.num_regions_reported = 0;
    if (!r.in_collision) {
      m.status = PairContactModel::Status::kFree;
      continue;
    }
    if (!r.valid || !r.translation_W.allFinite() || !std::isfinite(r.depth)) {
      m.status = PairContactModel::Status::kInvalid;
      ++invalid_count_;
      continue;
    }
    m.status = PairContactModel::Status::kContact;
    BuildModel(r, object, X_WT, &m);
  }
  out->query_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t_start).count();
}

void ContactGeometry::FindPressurePoints(const pd::PenetrationResult& r, const SceneObject& object) {
  inside_.clear();
  depth_points_.clear();
  // A sphere's contact forces all pass through its centre: its region
  // points are exact and sparse surface samples would only add error.
  if (tool_->kind() == pd::ShapeKind::kSphere) return;
  const pd::Geometry& g = *object.geometry;
  const bool is_mesh = g.model() != nullptr;
  if (g.kind() == pd::ShapeKind::kMesh && !g.model()->closed()) return;  // containment is meaningless
  // Depth of point p_G below region j's plane, d_j - n_j·(X_WG p_G - p_j),
  // as offset_j - n_Gj·p_G: one dot product per point and region, and only
  // the points below some plane are posed in W (large meshes: most are not).
  std::array<Vector3, pd::kMaxContactRegions> n_G;
  std::array<double, pd::kMaxContactRegions> offset;
  const Matrix3 R_GW = X_WG_.linear().transpose();
  for (int j = 0; j < r.num_regions; ++j) {
    const pd::ContactRegion& region = r.regions[j];
    n_G[j] = R_GW * region.n_W;
    offset[j] = region.local_depth - region.n_W.dot(X_WG_.translation() - region.p_W);
  }
  const std::vector<Vector3>& points_G = tool_->surface_points();
  for (size_t v = 0; v < points_G.size(); ++v) {
    double e_max = 0.0;
    for (int j = 0; j < r.num_regions; ++j) e_max = std::max(e_max, offset[j] - n_G[j].dot(points_G[v]));
    if (e_max > 0.0) {
      p_WV_[v] = X_WG_ * points_G[v];
      depth_points_.emplace_back(e_max, static_cast<int>(v));
    }
  }
  if (is_mesh && static_cast<int>(depth_points_.size()) > kMaxMeshContainmentTests) {
    std::nth_element(depth_points_.begin(), depth_points_.begin() + kMaxMeshContainmentTests,
                     depth_points_.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    depth_points_.resize(kMaxMeshContainmentTests);
  }
  const Isometry3 X_SW = object.X_WS.inverse();
  for (const auto& [e, v] : depth_points_) {
    if (g.Contains(X_SW * p_WV_[v])) inside_.push_back(v);
  }
}

void ContactGeometry::BuildModel(const pd::PenetrationResult& r, const SceneObject& object,
                                 const Isometry3& X_WT, PairContactModel* m) {
  const double k = params_.stiffness, b = params_.damping, s = params_.torque_scale;
  const Vector3& p_WT = X_WT.translation();
  m->depth = r.depth;
  m->n_W = r.normal_W;
  m->num_regions_reported = r.num_regions;
  m->pressure_centre = params_.torque_model == TorqueModel::kPressureCentre;
  m->q_W = p_WT;

  int n_regions = 0;
  double depth_sum = 0.0;
  for (int j = 0; j < r.num_regions; ++j) {
    const pd::ContactRegion& region = r.regions[j];
    if (region.local_depth > 0.0 && region.p_W.allFinite()) ++n_regions, depth_sum += region.local_depth;
  }
  if (n_regions == 0 || s == 0.0) return;
  const bool pressure_centre = m->pressure_centre;
  const double k_i = pressure_centre ? k / n_regions : k;
  const double b_i = pressure_centre ? b / n_regions : b;
  if (pressure_centre) FindPressurePoints(r, object);

  double deepest = 0.0;
  for (int j = 0; j < r.num_regions; ++j) {
    const pd::ContactRegion& region = r.regions[j];
    if (!(region.local_depth > 0.0) || !region.p_W.allFinite()) continue;
    const Vector3& n = region.n_W;
    // Centre of pressure c and the weighted mean of (r x n)(r x n)^T.
    double weight = 0.0;
    Vector3 c_sum = Vector3::Zero();
    Matrix3 aaT_sum = Matrix3::Zero();
    Vector3 arm;
    bool region_point_inside = false;
    if (pressure_centre) {
      for (int v : inside_) {
        const double e = region.local_depth - n.dot(p_WV_[v] - region.p_W);
        if (e <= 0.0) continue;
        weight += e;
        c_sum += e * p_WV_[v];
        arm = (p_WV_[v] - p_WT).cross(n);
        aaT_sum += e * arm * arm.transpose();
        region_point_inside |= (p_WV_[v] - region.p_W).squaredNorm() <= same_point_tol2_;
      }
    }
    // The region's own point, unless it is one of the pressure points (a
    // corner of a box or a mesh vertex, picked among equally deep ones by the
    // solver's tie-breaking: counting it twice would make the centre follow
    // that choice, which flips with the faintest tilt and chatters).
    if (!region_point_inside) {
      const double w = kRegionPointWeight * region.local_depth;
      weight += w;
      c_sum += w * region.p_W;
      arm = (region.p_W - p_WT).cross(n);
      aaT_sum += w * arm * arm.transpose();
    }
    PairContactModel::Region& out = m->regions[m->num_regions++];
    out.n_W = n;
    out.depth = region.local_depth;
    out.p_W = region.p_W;
    out.c_W = c_sum / weight;
    out.weight = region.local_depth / depth_sum;
    out.k = k_i;
    out.b = b_i;
    out.aaT = aaT_sum / weight;
    if (region.local_depth > deepest) deepest = region.local_depth, m->q_W = region.p_W;
  }
}

}  // namespace haptics
