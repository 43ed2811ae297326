#pragma once
// The local contact model of one (tool, object) pair: what one PD answer says
// about the contact, in a form the servo tick can evaluate at any nearby tool
// pose without asking the geometry again (Otaduy and Lin, IEEE T-RO 2006).
//
// Built from a PD answer at the tool pose X_WT0 (contact_geometry.h): per
// contact region i its plane in translation space (unit normal n_i, local
// depth d_i at X_WT0) and the point c_i of the tool where its force acts
// (centre of pressure, or the region point; see penalty_wrench.h), and for
// the whole object the PD depth d and direction n acting at the depth-
// weighted mean centre c. At the tool's current pose X_WT a tool point x
// (in W at X_WT0) sits at x' = p_WT + R_WT R_WT0^T (x - p_WT0); the object is
// static, so each plane gives the depth at the region's contact point p_i
// (the tool's deepest point of the region) and the PD at the deepest
// region's point q:
//   d_i' = d_i - n_i · (p_i' - p_i),   d' = d - n · (q' - q),
// exact in translation and first order in rotation (the planes do not turn
// with the tool); the regional forces act at the moved centres c_i'. Forces, torques and the implicit step's K and D then follow
// the penalty formulas of penalty_wrench.h with d_i', c_i' and the tool's
// current velocity. At X_WT = X_WT0 the evaluation reproduces the direct
// formula exactly, so a synchronous loop (model rebuilt every tick) renders
// what it always did, and between updates of an asynchronous one force and
// torque move continuously with the tool.
//
// Value type, fixed size: copied between threads without allocating.
#include <array>
#include <cstdint>

#include "haptics/scene/scene_config.h"
#include "haptics/tool/spatial.h"
#include "pd_core/polydepth/penetration_result.h"

namespace haptics {

struct PairContactModel {
  enum class Status : uint8_t {
    kFree,     // queried, not in contact
    kContact,  // a verified PD answer: the model below holds
    kInvalid,  // in contact but the answer could not be verified (no model)
  };
  struct Region {
    Vector3 n_W = Vector3::UnitZ();  // unit normal (escape side)
    double depth = 0.0;              // local depth d_i at X_WT0 (m), > 0
    Vector3 p_W = Vector3::Zero();   // its contact point on the tool, at X_WT0
    Vector3 c_W = Vector3::Zero();   // where its force acts, at X_WT0
    double weight = 0.0;             // d_i / sum_j d_j (for the mean centre)
    double k = 0.0, b = 0.0;         // its share of stiffness (N/m) and damping (N·s/m)
    Matrix3 aaT = Matrix3::Zero();   // weighted mean of (r x n)(r x n)^T over its pressure points (m²)
  };

  int object = -1;
  Status status = Status::kFree;
  Isometry3 X_WT0 = Isometry3::Identity();  // tool pose of the query
  double depth = 0.0;                       // PD depth at X_WT0 (m)
  Vector3 n_W = Vector3::Zero();            // PD direction (unit)
  Vector3 q_W = Vector3::Zero();            // point of the deepest region at X_WT0 (tool origin if none)
  int num_regions_reported = 0;             // regions PolyDepth reported (all, for ContactSummary)
  int num_regions = 0;                      // regions with positive depth (below)
  bool pressure_centre = true;              // TorqueModel::kPressureCentre
  std::array<Region, pd::kMaxContactRegions> regions{};
};

// Accumulated contact of all objects at one tool state.
struct ContactSummary {
  LinearizedWrench wrench;  // on the tool, at its origin, in W, with its K and D
  double max_depth = 0.0;   // deepest PD over objects (m)
  int num_regions = 0;      // contact regions summed over objects
  int num_candidates = 0;   // objects the broad phase kept (PD queried)
  int num_culled = 0;       // objects the broad phase skipped
  int num_in_contact = 0;   // objects with a verified contact (or a held one)
  int num_invalid = 0;      // objects whose newest PD answer was not verified
  int num_held = 0;         // of those, objects rendered from their last valid answer
};

// Adds the wrench of `model` at the tool's current state, times `scale`
// (0..1: hold decay and ageing), to *out. contact.stiffness, damping and
// torque_scale are read from `params`; the region shares were fixed at build.
void EvaluatePairContactModel(const PairContactModel& model, const RigidState& tool,
                              const ContactConfig& params, double scale, ContactSummary* out);

}  // namespace haptics
