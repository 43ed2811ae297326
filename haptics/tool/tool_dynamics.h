#pragma once
// The simulated tool T: a rigid body integrated at the servo period with a
// linearly-implicit (backward) Euler step. The wrenches acting on it come
// with their stiffness K and damping D (spatial.h: LinearizedWrench), and the
// next velocity V' = [v'; w'] solves
//
//   (M + h D + h² K) V' = (M + h D) V + h (w0 + gravity - w x I w),
//
// then p' = p + h v', R' = exp(h w') R. A spring-damper treated this way is
// unconditionally stable (it only ever loses energy), whatever the gains and
// the step, which is why the coupling and the contact are passed in this form.
//
// Mass properties are rendering parameters: the mass sits at the tool origin
// (where the coupling and contact wrenches are referred) and I_T is about that
// origin, in T. Gyroscopic and gravity terms are explicit.
#include <cstdint>

#include "haptics/tool/spatial.h"

namespace haptics {

class ToolDynamics {
 public:
  // mass (kg) > 0; I_T (kg·m²) symmetric positive definite; gravity_W (m/s²).
  ToolDynamics(double mass, const Matrix3& I_T, const Vector3& gravity_W = Vector3::Zero());

  // Places the tool at X_WT, at rest.
  void Reset(const Isometry3& X_WT);

  // Advances by h (s) under `wrench` (at the tool origin, in W).
  void Step(double h, const LinearizedWrench& wrench);

  const RigidState& state() const { return state_; }
  double mass() const { return mass_; }
  const Matrix3& I_T() const { return I_T_; }
  // Rotational inertia about the origin in W at the current pose.
  Matrix3 I_W() const;
  double KineticEnergy() const;  // J
  // Steps whose solve gave a non-finite velocity (the tool was then stopped).
  int64_t nonfinite_steps() const { return nonfinite_steps_; }

 private:
  double mass_;
  Matrix3 I_T_;
  Vector3 gravity_W_;
  RigidState state_;
  Quaternion q_WT_ = Quaternion::Identity();  // kept normalised; state_.X_W follows it
  int64_t nonfinite_steps_ = 0;
};

}  // namespace haptics
