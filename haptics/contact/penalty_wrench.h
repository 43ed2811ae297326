#pragma once
// Penalty contact between the tool and the scene objects from penetration
// depth: a broad phase (broad_phase.h) picks the objects the tool's motion
// over the tick can reach, and one warm-started pd::PairPdSolver per object
// (closed form, GJK/EPA or PolyDepth, whichever the pair's kinds need) gives
// the PD of each. Culled objects cost nothing; their warm start is dropped.
//
// Force, per object in contact, with PD depth d along the unit escape
// direction n (result.normal_W: moving the tool by d n separates it):
//   f_W = max(0, k d - b (v_WT · n)) n        (pushes out, never pulls)
// with k the stiffness (N/m) and b the damping (N·s/m).
//
// Torque, about the tool origin p_WT, from the local PDs of the object's
// contact regions i (local depth d_i, normal n_i, contact point p_i), with
// regional forces f_i n_i, f_i = max(0, k_i d_i - b_i (v_i · n_i)), v_i the
// tool's velocity at the point where region i acts, and s the torque scale.
// Two models (ContactConfig::torque_model):
//  - kRegionPoints: tau_W = s * sum_i (p_i - p_WT) x f_i n_i with k_i = k,
//    b_i = b. The plain formula. Its torque grows with the number of regions
//    PolyDepth reports (a line contact split into 4 regions turns the tool 4
//    times harder than its force would), and it jumps whenever the region's
//    features change: a box resting flat has its region at one corner or the
//    opposite one depending on the sign of a tiny tilt, a bang-bang torque
//    that chatters at any gain.
//  - kPressureCentre (default): each region acts at its centre of pressure
//    c_i: the tool's pressure points (pd::Geometry::surface_points(): mesh
//    vertices, box lattice points, rings on round shapes) inside the object
//    (Geometry::Contains; none for an open mesh) and below the region's
//    contact plane, weighted by their depth below it, e_v = d_i -
//    n_i · (v - p_i), plus p_i with a small weight (0.01 d_i; the only point
//    when no pressure point is inside, e.g. an edge-edge contact) unless p_i
//    is itself one of those pressure points (within 1e-9 of the tool's
//    size). A sphere tool uses p_i alone: its forces pass through its centre. It moves
//    continuously as the tool tilts and reduces to p_i for a vertex contact.
//    The regions share the stiffness, k_i = k / N and b_i = b / N for N
//    regions, and the torque is the moment of the object's PD force f_W
//    applied at their depth-weighted mean centre c = sum_i d_i c_i / sum_i d_i,
//    plus the couple of the regional forces about it:
//      tau_W = s * [ (c - p_WT) x f_W + sum_i (c_i - c) x f_i n_i ].
//    Force and torque are thus consistent, a flat face rests without chatter,
//    opposite walls still resist a tilt (the couple), and a region that
//    toggles at the edge of PolyDepth's contact tolerance next to the others
//    barely changes the torque.
//
// For the implicit tool step the stiffness is k n n^T for translation and
// s sum_i k_i <(r x n_i)(r x n_i)^T> for rotation, <.> the weighted mean over
// the region's pressure points r (damping likewise with b, pushing terms
// only); translation-rotation cross terms are dropped, which keeps K and D
// symmetric positive semi-definite (all the step needs).
//
// The geometry (broad phase, PD, pressure points) is ContactGeometry's
// (contact_geometry.h); each answer becomes a local model per pair
// (pair_contact_model.h) that LocalContactModel (local_contact_model.h)
// evaluates at the tool's state. PenaltyContact is the synchronous pair of the
// two: query and evaluate at the same state, every call; the models are then
// exact (the formulas above).
//
// An answer PolyDepth could not verify (result.valid == false) does not drop
// the object's force: the pair's last valid model is held, evaluated at the
// current pose, decaying to zero over contact.invalid_hold_ms (counted, and
// flagged by the renderer). A pair with no valid answer yet contributes
// nothing. The wrench is the sum over all objects in contact.
#include <cstdint>
#include <memory>
#include <vector>

#include "haptics/scene/build_scene.h"
#include "haptics/contact/contact_geometry.h"
#include "haptics/contact/local_contact_model.h"
#include "haptics/contact/pair_contact_model.h"
#include "haptics/scene/scene_config.h"
#include "haptics/scene/scene_object.h"
#include "haptics/tool/spatial.h"
#include "pd_core/pair_pd_solver.h"
#include "pd_core/polydepth/penetration_result.h"

namespace haptics {

// Local-model options for a servo period dt (s) from the contact config and
// the device's rate limits.
LocalContactOptions MakeLocalContactOptions(const ContactConfig& contact, double max_force_rate,
                                            double max_torque_rate, double dt);

class PenaltyContact {
 public:
  // The tool geometry in its frame G, placed in the tool frame T by X_TG.
  // `local`: hold and ageing (default: hold over contact.invalid_hold_ms at 1 kHz).
  PenaltyContact(std::shared_ptr<const pd::Geometry> tool, const Isometry3& X_TG,
                 std::vector<SceneObject> objects, const ContactConfig& params,
                 pd::PolyDepthOptions options = {});
  PenaltyContact(const SceneModels& models, const ContactConfig& params,
                 pd::PolyDepthOptions options = {})
      : PenaltyContact(models.tool, models.X_TG, models.objects, params, options) {}

  // Contact at the tool's pose and velocity. The tool's previous pose (from
  // the previous call) and this one bound its motion for the broad phase.
  // The reference stays valid until the next call. Allocation-free once the
  // solvers' scratch has grown. Each call is one tick of the hold decay.
  const ContactSummary& Compute(const RigidState& tool);

  // Forget warm starts, held models and the previous pose (after the tool jumped).
  void ResetWarmStarts();

  int num_objects() const { return geometry_.num_objects(); }
  const SceneObject& object(int i) const { return geometry_.object(i); }
  const pd::PairPdSolver& solver(int i) const { return geometry_.solver(i); }
  const BroadPhase& broad_phase() const { return geometry_.broad_phase(); }
  // The last PD answer for object i (in_collision false if it was culled).
  const pd::PenetrationResult& last_result(int i) const { return geometry_.last_result(i); }
  int64_t invalid_count() const { return geometry_.invalid_count(); }
  int64_t query_count() const { return geometry_.query_count(); }
  const ContactConfig& params() const { return geometry_.params(); }
  ContactGeometry& geometry() { return geometry_; }
  LocalContactModel& local() { return local_; }
  const LocalContactModel& local() const { return local_; }
  int32_t last_flags() const { return flags_; }

 private:
  ContactGeometry geometry_;
  LocalContactModel local_;
  ContactSnapshot snapshot_;
  int64_t tick_ = 0;
  int32_t flags_ = 0;
};

}  // namespace haptics
