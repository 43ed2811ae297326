#pragma once
// Virtual coupling: a translational and a rotational spring-damper between
// the device handle D (pose X_WD from the probe) and the simulated tool T.
// The wrench on the tool, at its origin, in W, is
//
//   f_W   = sat_F(k_t e_W)     + b_t (v_WD - v_WT),  e_W     = p_WD - p_WT
//   tau_W = sat_T(k_r theta_W) + b_r (w_WD - w_WT),  theta_W = log(R_WD R_WT^T)
//
// (theta_W: the rotation vector taking the tool's orientation to the
// device's; sat_L(x) = x * min(1, L / |x|) keeps the direction). The device
// feels the reaction, -f_W and -tau_W: the coupling bounds the stiffness it
// must render by k_t and k_r whatever the contact stiffness, which keeps the
// device stable. The springs saturate at the device's max force and torque:
// the tool is never pushed harder than the device can push back, so pushing
// the handle far into an object cannot drive the tool deeper than
// max_force / contact stiffness (or through a thin wall).
#include <limits>

#include "haptics/scene/scene_config.h"
#include "haptics/tool/spatial.h"

namespace haptics {

class VirtualCoupling {
 public:
  // Spring saturation limits in N and N·m (default: none).
  explicit VirtualCoupling(const CouplingConfig& gains,
                           double max_spring_force = std::numeric_limits<double>::infinity(),
                           double max_spring_torque = std::numeric_limits<double>::infinity());

  // Wrench on the tool (see above).
  Wrench OnTool(const RigidState& device, const RigidState& tool) const;
  // The reaction on the device: what is sent to it, before conditioning.
  Wrench OnDevice(const RigidState& device, const RigidState& tool) const;
  // OnTool with its stiffness and damping in the tool's motion, for the
  // implicit step: diag(k_t, k_r) and diag(b_t, b_r) while the springs are
  // linear; a saturated spring is stiff only across its direction,
  // (L / |e|)(I - e e^T / |e|^2).
  LinearizedWrench Linearize(const RigidState& device, const RigidState& tool) const;

  // Potential energy of the (unsaturated) springs (J).
  double PotentialEnergy(const RigidState& device, const RigidState& tool) const;

  const CouplingConfig& gains() const { return gains_; }

 private:
  CouplingConfig gains_;
  double max_force_, max_torque_;
};

}  // namespace haptics
