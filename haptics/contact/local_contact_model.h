#pragma once
// The servo side of penalty contact: the local contact model of every pair in
// reach (pair_contact_model.h), built from the newest geometry answer
// (contact_geometry.h) and evaluated at the tool's current state every tick.
//
// - A new answer replaces the models. With `blend` on (the geometry thread
//   runs, so answers are older than the tick and arrive every few ticks) the
//   difference between the old models and the new ones at the current tool
//   state becomes a wrench offset that decays linearly to zero in as many
//   ticks as the device's force and torque rate limits need (at least one,
//   at most kMaxBlendTicks): a new answer never makes the contact wrench
//   jump faster than the device may change its output.
// - Hold-last-valid: a pair whose newest answer could not be verified keeps
//   its last valid model, evaluated at the current pose (so the wall keeps
//   pushing as the tool goes deeper), scaled down linearly from 1 to 0 over
//   `hold_ticks`. Flagged (kFlagContactHeld, with kFlagPdInvalid), counted.
//   A pair with no valid model to hold contributes nothing (flagged, counted).
// - Ageing: the models' age is the ticks since the query's tool pose was
//   taken. Past `max_age_ticks` (the geometry thread stalls) the contact
//   wrench ramps linearly to zero over `age_ramp_ticks` (kFlagModelStale,
//   counted); a fresh answer restores it (through the blend).
// Allocation-free after construction; single thread (the servo tick).
#include <cstdint>
#include <vector>

#include "haptics/contact/contact_geometry.h"
#include "haptics/contact/pair_contact_model.h"
#include "haptics/scene/scene_config.h"
#include "haptics/tool/spatial.h"

namespace haptics {

struct LocalContactOptions {
  bool blend = false;            // smooth model replacement (asynchronous geometry)
  double max_force_step = 1e9;   // N per tick the blend may change the force (device rate x dt)
  double max_torque_step = 1e9;  // N·m per tick
  int64_t hold_ticks = 200;      // hold-last-valid decay length
  int64_t max_age_ticks = 100;   // older models start ramping out
  int64_t age_ramp_ticks = 50;   // ... to zero over this many ticks
};

struct LocalContactCounts {
  int64_t updates = 0;          // answers taken
  int64_t invalid_answers = 0;  // pair answers not verified (in the answers taken)
  int64_t held_ticks = 0;       // ticks rendering at least one held pair
  int64_t dropped_ticks = 0;    // ticks with an invalid pair and nothing to hold
  int64_t stale_ticks = 0;      // ticks with the models past max age
  int64_t blend_ticks = 0;      // ticks with a replacement offset decaying
  int64_t outdated_answers = 0; // answers for a pose older than the models in use: dropped
};

class LocalContactModel {
 public:
  static constexpr int64_t kMaxBlendTicks = 50;

  LocalContactModel(int num_objects, const ContactConfig& params, const LocalContactOptions& options);

  // Takes `answer` (nullptr: no new one this tick) and evaluates the models
  // at `tool` for servo tick `tick`. An answer whose request tick is not
  // newer than the models in use is dropped and counted (outdated_answers):
  // a worker's answer left untaken while the queries ran in the tick must
  // not bring back the contact of a pose seconds old. ORs kFlagPdInvalid, kFlagContactHeld and
  // kFlagModelStale into *flags. The reference stays valid until the next call.
  const ContactSummary& Update(const ContactSnapshot* answer, const RigidState& tool, int64_t tick,
                               int32_t* flags);

  // Drops every model (the tool jumped; the next answer starts afresh).
  void Reset();

  void set_blend(bool blend) { options_.blend = blend; }
  const LocalContactOptions& options() const { return options_; }
  const LocalContactCounts& counts() const { return counts_; }
  // Ticks since the tool pose of the models in use was taken (-1: none yet).
  int64_t model_age(int64_t tick) const { return model_tick_ < 0 ? -1 : tick - model_tick_; }
  const ContactSummary& summary() const { return summary_; }
  // The last Update's work in model terms (pairs taken from the answer,
  // pairs and regions evaluated): its cost is a fixed amount per term, so
  // the servo loop can tell an overrun of this work from time the platform
  // charged to the thread (miss_cause.h).
  int64_t last_update_terms() const { return terms_; }

 private:
  struct Pair {
    PairContactModel model;         // last valid (status kContact) or kFree
    int64_t invalid_since = -1;     // tick of the first invalid answer of a run, -1: none
    bool active = false;            // in active_
  };
  void Accept(const ContactSnapshot& answer, int64_t tick);
  // Sum of the active models at `tool` into *out (counts fields too).
  void Evaluate(const RigidState& tool, int64_t tick, ContactSummary* out);

  ContactConfig params_;
  LocalContactOptions options_;
  std::vector<Pair> pairs_;
  std::vector<int> active_, next_active_;  // objects with a model or an invalid answer
  std::vector<int64_t> seen_;              // per object: update number it was last answered in
  int64_t update_ = 0;
  int64_t model_tick_ = -1;
  int num_candidates_ = 0, num_culled_ = 0;
  ContactSummary summary_;
  ContactSummary scratch_;
  // Replacement blend: offset added to the contact wrench, and its per-tick step.
  Wrench offset_, offset_step_;
  int64_t offset_ticks_left_ = 0;
  LocalContactCounts counts_;
  int64_t terms_ = 0;
};

}  // namespace haptics
