#include "haptics/penalty_wrench.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace haptics {
namespace {

// Weight of the region's own point among its pressure points, per metre of
// its local depth: small, so that pressure points dominate when there are any.
constexpr double kRegionPointWeight = 0.01;
// At most this many containment tests per mesh object and tick (the deepest
// candidates), which bounds the cost for large flat contacts. Primitives
// answer containment in closed form and are not capped.
constexpr int kMaxMeshContainmentTests = 48;

}  // namespace

PenaltyContact::PenaltyContact(std::shared_ptr<const pd::Geometry> tool, const Isometry3& X_TG,
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
  candidate_tick_.assign(objects_.size(), -1);
  const double same_point_tol = 1e-9 * tool_->radius();
  same_point_tol2_ = same_point_tol * same_point_tol;
  const size_t np = tool_->surface_points().size();
  p_WV_.resize(np);
  depth_points_.reserve(np);
  inside_.reserve(np);
}

void PenaltyContact::ResetWarmStarts() {
  for (auto& solver : solvers_) solver->ResetWarmStart();
  have_previous_ = false;
}

const ContactSummary& PenaltyContact::Compute(const RigidState& tool) {
  summary_ = ContactSummary{};
  ++tick_;
  const Isometry3 X_WG = tool.X_W * X_TG_;
  X_WG_ = X_WG;

  // Broad phase over the tool's motion since the previous call.
  const WorldBox box_W = BoundingBoxInWorld(*tool_, X_WG);
  const WorldBox swept_W = (have_previous_ ? box_W.Joined(previous_box_W_) : box_W).Grown(params_.cull_margin);
  previous_box_W_ = box_W;
  have_previous_ = true;
  candidates_prev_.swap(candidates_now_);
  broad_phase_.Query(swept_W, &candidates_now_);
  for (int i : candidates_now_) candidate_tick_[i] = tick_;
  for (int i : candidates_prev_) {
    if (candidate_tick_[i] == tick_) continue;
    // Out of reach again: the next contact starts cold.
    solvers_[i]->ResetWarmStart();
    results_[i] = pd::PenetrationResult{};
  }
  summary_.num_candidates = static_cast<int>(candidates_now_.size());
  summary_.num_culled = num_objects() - summary_.num_candidates;

  for (int i : candidates_now_) {
    const SceneObject& object = objects_[i];
    ++query_count_;
    results_[i] = solvers_[i]->Solve(X_WG, object.X_WS, /*coherent=*/true);
    const pd::PenetrationResult& r = results_[i];
    if (!r.in_collision) continue;
    if (!r.valid || !r.translation_W.allFinite() || !std::isfinite(r.depth)) {
      ++summary_.num_invalid;
      ++invalid_count_;
      continue;
    }
    ++summary_.num_in_contact;
    AddObjectContact(r, object, tool);
  }
  return summary_;
}

void PenaltyContact::FindPressurePoints(const pd::PenetrationResult& r, const SceneObject& object) {
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

void PenaltyContact::AddObjectContact(const pd::PenetrationResult& r, const SceneObject& object,
                                      const RigidState& tool) {
  const double k = params_.stiffness, b = params_.damping, s = params_.torque_scale;
  LinearizedWrench& lw = summary_.wrench;
  summary_.max_depth = std::max(summary_.max_depth, r.depth);
  summary_.num_regions += r.num_regions;

  // Force from the (global) PD along its direction.
  Vector3 object_force = Vector3::Zero();
  if (r.depth > 0.0) {
    const Vector3& n = r.normal_W;
    const double f_n = k * r.depth - b * tool.v_W.dot(n);
    if (f_n > 0.0) {
      object_force = f_n * n;
      lw.w0.f_W += object_force;
      // Moving the tool by dp along n reduces the depth by n·dp.
      const Matrix3 nnT = n * n.transpose();
      lw.K.topLeftCorner<3, 3>() += k * nnT;
      lw.D.topLeftCorner<3, 3>() += b * nnT;
    }
  }

  // Torque from the local PDs.
  int n_regions = 0;
  double depth_sum = 0.0;
  for (int j = 0; j < r.num_regions; ++j) {
    const pd::ContactRegion& region = r.regions[j];
    if (region.local_depth > 0.0 && region.p_W.allFinite()) ++n_regions, depth_sum += region.local_depth;
  }
  if (n_regions == 0 || s == 0.0) return;
  const bool pressure_centre = params_.torque_model == TorqueModel::kPressureCentre;
  const double k_i = pressure_centre ? k / n_regions : k;
  const double b_i = pressure_centre ? b / n_regions : b;
  if (pressure_centre) FindPressurePoints(r, object);

  const Vector3& p_WT = tool.X_W.translation();
  Vector3 c_mean = Vector3::Zero();  // depth-weighted mean centre of pressure
  Vector3 tau_regions = Vector3::Zero();
  Vector3 force_regions = Vector3::Zero();
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
    const Vector3 c = c_sum / weight;
    c_mean += (region.local_depth / depth_sum) * c;
    const Vector3 v_contact = tool.v_W + tool.w_W.cross(c - p_WT);
    const double f_i = k_i * region.local_depth - b_i * v_contact.dot(n);
    if (f_i <= 0.0) continue;
    // Moments about p_WT; the couple about c_mean is formed below.
    tau_regions += f_i * (c - p_WT).cross(n);
    force_regions += f_i * n;
    // Turning the tool by dtheta reduces the depth at r by (r x n)·dtheta.
    const Matrix3 aaT = aaT_sum / weight;
    lw.K.bottomRightCorner<3, 3>() += s * k_i * aaT;
    lw.D.bottomRightCorner<3, 3>() += s * b_i * aaT;
  }
  if (pressure_centre) {
    // sum_i (c_i - c) x f_i n_i = sum_i (c_i - p) x f_i n_i - (c - p) x sum_i f_i n_i.
    const Vector3 r_mean = c_mean - p_WT;
    lw.w0.tau_W += s * (r_mean.cross(object_force) + tau_regions - r_mean.cross(force_regions));
  } else {
    lw.w0.tau_W += s * tau_regions;
  }
}

}  // namespace haptics
