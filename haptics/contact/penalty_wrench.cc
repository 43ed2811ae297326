#include "haptics/contact/penalty_wrench.h"

#include <algorithm>
#include <cmath>

namespace haptics {

LocalContactOptions MakeLocalContactOptions(const ContactConfig& contact, double max_force_rate,
                                            double max_torque_rate, double dt) {
  LocalContactOptions o;
  auto ticks = [dt](double s) { return std::max<int64_t>(1, std::llround(s / dt)); };
  o.hold_ticks = ticks(contact.invalid_hold_s);
  o.max_age_ticks = ticks(contact.model_max_age_s);
  o.age_ramp_ticks = ticks(contact.model_age_ramp_s);
  if (max_force_rate > 0.0) o.max_force_step = max_force_rate * dt;
  if (max_torque_rate > 0.0) o.max_torque_step = max_torque_rate * dt;
  return o;
}

PenaltyContact::PenaltyContact(std::shared_ptr<const pd::Geometry> tool, const Isometry3& X_TG,
                               std::vector<SceneObject> objects, const ContactConfig& params,
                               pd::PolyDepthOptions options)
    : geometry_(std::move(tool), X_TG, std::move(objects), params, options),
      local_(geometry_.num_objects(), params, MakeLocalContactOptions(params, 0.0, 0.0, 1e-3)) {
  snapshot_.Reserve(geometry_.num_objects());
}

void PenaltyContact::ResetWarmStarts() {
  geometry_.ResetWarmStarts();
  local_.Reset();
}

const ContactSummary& PenaltyContact::Compute(const RigidState& tool) {
  ++tick_;
  geometry_.Query(tool.X_W, tick_, &snapshot_);
  flags_ = 0;
  return local_.Update(&snapshot_, tool, tick_, &flags_);
}

}  // namespace haptics
