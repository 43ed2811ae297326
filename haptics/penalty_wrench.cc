#include "haptics/penalty_wrench.h"

#include <algorithm>
#include <cmath>

#include "pd_core/point_in_mesh.h"

namespace haptics {
namespace {

// Weight of the region's own point among its pressure points, per metre of
// its local depth: small, so that vertices dominate when there are any.
constexpr double kRegionPointWeight = 0.01;
// At most this many containment tests per object and tick (the deepest
// candidates), which bounds the cost for large flat contacts.
constexpr int kMaxContainmentTests = 48;

}  // namespace

PenaltyContact::PenaltyContact(std::shared_ptr<const pd::CollisionModel> tool,
                               std::vector<SceneObject> objects, const ContactConfig& params,
                               pd::PolyDepthOptions options)
    : tool_(std::move(tool)), objects_(std::move(objects)), params_(params) {
  for (const SceneObject& object : objects_)
    solvers_.push_back(std::make_unique<pd::PolyDepthSolver>(tool_, object.model, options));
  results_.resize(objects_.size());
  const size_t nv = tool_->mesh().vertices.size();
  p_WV_.resize(nv);
  candidates_.reserve(nv);
  inside_.reserve(nv);
}

void PenaltyContact::ResetWarmStarts() {
  for (auto& solver : solvers_) solver->ResetWarmStart();
}

const ContactSummary& PenaltyContact::Compute(const RigidState& tool) {
  summary_ = ContactSummary{};
  const Isometry3& X_WT = tool.X_W;
  const Vector3 p_WTc = X_WT * tool_->center();  // tool's bounding-sphere centre
  bool vertices_posed = false;
  for (size_t i = 0; i < objects_.size(); ++i) {
    const SceneObject& object = objects_[i];
    const Vector3 p_WSc = object.X_WS * object.model->center();
    const double reach = tool_->radius() + object.model->radius() + params_.cull_margin;
    if ((p_WTc - p_WSc).squaredNorm() > reach * reach) {
      // Cannot touch: costs nothing, and the next contact starts cold.
      solvers_[i]->ResetWarmStart();
      results_[i] = pd::PenetrationResult{};
      continue;
    }
    ++summary_.num_queried;
    ++query_count_;
    results_[i] = solvers_[i]->Solve(X_WT, object.X_WS, /*coherent=*/true);
    const pd::PenetrationResult& r = results_[i];
    if (!r.in_collision) continue;
    if (!r.valid || !r.translation_W.allFinite() || !std::isfinite(r.depth)) {
      ++summary_.num_invalid;
      ++invalid_count_;
      continue;
    }
    ++summary_.num_in_contact;
    if (!vertices_posed) {
      const auto& vertices = tool_->mesh().vertices;
      for (size_t v = 0; v < vertices.size(); ++v) p_WV_[v] = X_WT * vertices[v];
      vertices_posed = true;
    }
    AddObjectContact(r, object, tool);
  }
  return summary_;
}

void PenaltyContact::FindPressurePoints(const pd::PenetrationResult& r, const SceneObject& object) {
  inside_.clear();
  candidates_.clear();
  if (!object.model->closed()) return;  // containment is meaningless
  for (size_t v = 0; v < p_WV_.size(); ++v) {
    double e_max = 0.0;
    for (int j = 0; j < r.num_regions; ++j) {
      const pd::ContactRegion& region = r.regions[j];
      e_max = std::max(e_max, region.local_depth - region.n_W.dot(p_WV_[v] - region.p_W));
    }
    if (e_max > 0.0) candidates_.emplace_back(e_max, static_cast<int>(v));
  }
  if (static_cast<int>(candidates_.size()) > kMaxContainmentTests) {
    std::nth_element(candidates_.begin(), candidates_.begin() + kMaxContainmentTests,
                     candidates_.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    candidates_.resize(kMaxContainmentTests);
  }
  const Isometry3 X_SW = object.X_WS.inverse();
  for (const auto& [e, v] : candidates_) {
    if (pd::PointInsideMesh(*object.model, X_SW * p_WV_[v])) inside_.push_back(v);
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
    double weight = kRegionPointWeight * region.local_depth;
    Vector3 c_sum = weight * region.p_W;
    Vector3 arm = (region.p_W - p_WT).cross(n);
    Matrix3 aaT_sum = weight * arm * arm.transpose();
    if (pressure_centre) {
      for (int v : inside_) {
        const double e = region.local_depth - n.dot(p_WV_[v] - region.p_W);
        if (e <= 0.0) continue;
        weight += e;
        c_sum += e * p_WV_[v];
        arm = (p_WV_[v] - p_WT).cross(n);
        aaT_sum += e * arm * arm.transpose();
      }
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
