#include "haptics/contact/pair_contact_model.h"

#include <algorithm>

namespace haptics {

void EvaluatePairContactModel(const PairContactModel& m, const RigidState& tool,
                              const ContactConfig& params, double scale, ContactSummary* out) {
  if (m.status != PairContactModel::Status::kContact || !(scale > 0.0)) return;
  const double k = params.stiffness, b = params.damping, s = params.torque_scale;
  LinearizedWrench& lw = out->wrench;
  const Vector3& p_WT = tool.X_W.translation();
  // Tool points move rigidly from X_WT0 to X_WT: x' = p_WT + R (x - p_WT0).
  const Matrix3 R = tool.X_W.linear() * m.X_WT0.linear().transpose();
  const Vector3& p_WT0 = m.X_WT0.translation();
  auto moved = [&](const Vector3& x) -> Vector3 { return p_WT + R * (x - p_WT0); };

  const double depth = m.depth - m.n_W.dot(moved(m.q_W) - m.q_W);
  out->max_depth = std::max(out->max_depth, std::max(0.0, depth));
  out->num_regions += m.num_regions_reported;

  // Force from the object's PD along its direction.
  Vector3 object_force = Vector3::Zero();
  if (depth > 0.0) {
    const Vector3& n = m.n_W;
    const double f_n = k * depth - b * tool.v_W.dot(n);
    if (f_n > 0.0) {
      object_force = scale * f_n * n;
      lw.w0.f_W += object_force;
      const Matrix3 nnT = n * n.transpose();
      lw.K.topLeftCorner<3, 3>() += scale * k * nnT;
      lw.D.topLeftCorner<3, 3>() += scale * b * nnT;
    }
  }
  if (m.num_regions == 0 || s == 0.0) return;

  // Torque from the regions' planes at their moved centres.
  Vector3 c_mean = Vector3::Zero();
  Vector3 tau_regions = Vector3::Zero();
  Vector3 force_regions = Vector3::Zero();
  for (int j = 0; j < m.num_regions; ++j) {
    const PairContactModel::Region& region = m.regions[j];
    const Vector3& n = region.n_W;
    const Vector3 c = moved(region.c_W);
    c_mean += region.weight * c;
    const double d = region.depth - n.dot(moved(region.p_W) - region.p_W);
    const Vector3 v_contact = tool.v_W + tool.w_W.cross(c - p_WT);
    const double f_i = scale * (region.k * d - region.b * v_contact.dot(n));
    if (f_i <= 0.0) continue;
    tau_regions += f_i * (c - p_WT).cross(n);
    force_regions += f_i * n;
    lw.K.bottomRightCorner<3, 3>() += scale * s * region.k * region.aaT;
    lw.D.bottomRightCorner<3, 3>() += scale * s * region.b * region.aaT;
  }
  if (m.pressure_centre) {
    // sum_i (c_i - c) x f_i n_i = sum_i (c_i - p) x f_i n_i - (c - p) x sum_i f_i n_i.
    const Vector3 r_mean = c_mean - p_WT;
    lw.w0.tau_W += s * (r_mean.cross(object_force) + tau_regions - r_mean.cross(force_regions));
  } else {
    lw.w0.tau_W += s * tau_regions;
  }
}

}  // namespace haptics
