#include "haptics/contact/local_contact_model.h"

#include <algorithm>
#include <cmath>

#include "haptics/io/wrench_output.h"

namespace haptics {

LocalContactModel::LocalContactModel(int num_objects, const ContactConfig& params,
                                     const LocalContactOptions& options)
    : params_(params), options_(options), pairs_(static_cast<size_t>(num_objects)),
      seen_(static_cast<size_t>(num_objects), -1) {
  active_.reserve(static_cast<size_t>(num_objects));
  next_active_.reserve(static_cast<size_t>(num_objects));
}

void LocalContactModel::Reset() {
  for (int i : active_) pairs_[i] = Pair{};
  active_.clear();
  model_tick_ = -1;
  offset_ = offset_step_ = Wrench{};
  offset_ticks_left_ = 0;
}

void LocalContactModel::Accept(const ContactSnapshot& answer, int64_t tick) {
  ++update_;
  ++counts_.updates;
  model_tick_ = answer.request_tick;
  num_candidates_ = answer.num_candidates;
  num_culled_ = answer.num_culled;
  next_active_.clear();
  terms_ += answer.num_pairs + static_cast<int64_t>(active_.size());
  for (int e = 0; e < answer.num_pairs; ++e) {
    const PairContactModel& m = answer.pairs[e];
    Pair& pair = pairs_[m.object];
    seen_[m.object] = update_;
    switch (m.status) {
      case PairContactModel::Status::kContact:
        pair.model = m;
        pair.invalid_since = -1;
        break;
      case PairContactModel::Status::kFree:
        pair.model.status = PairContactModel::Status::kFree;
        pair.invalid_since = -1;
        break;
      case PairContactModel::Status::kInvalid:
        ++counts_.invalid_answers;
        // Keep the last valid model (if any): the wall keeps pushing.
        if (pair.invalid_since < 0) pair.invalid_since = tick;
        break;
    }
    const bool keep = pair.model.status == PairContactModel::Status::kContact || pair.invalid_since >= 0;
    pair.active = keep;
    if (keep) next_active_.push_back(m.object);
  }
  // Objects out of reach in this answer: no contact.
  for (int i : active_) {
    if (seen_[i] != update_) pairs_[i] = Pair{};
  }
  active_.swap(next_active_);
}

void LocalContactModel::Evaluate(const RigidState& tool, int64_t tick, ContactSummary* out) {
  *out = ContactSummary{};
  out->num_candidates = num_candidates_;
  out->num_culled = num_culled_;
  for (int i : active_) {
    Pair& pair = pairs_[i];
    const bool has_model = pair.model.status == PairContactModel::Status::kContact;
    double scale = 1.0;
    if (pair.invalid_since >= 0) {
      ++out->num_invalid;
      if (!has_model) continue;
      const double held = static_cast<double>(tick - pair.invalid_since);
      scale = std::max(0.0, 1.0 - held / static_cast<double>(std::max<int64_t>(options_.hold_ticks, 1)));
      if (scale <= 0.0) continue;
      ++out->num_held;
    }
    ++out->num_in_contact;
    terms_ += 1 + pair.model.num_regions;
    EvaluatePairContactModel(pair.model, tool, params_, scale, out);
  }
}

const ContactSummary& LocalContactModel::Update(const ContactSnapshot* answer, const RigidState& tool,
                                                int64_t tick, int32_t* flags) {
  terms_ = static_cast<int64_t>(active_.size());
  if (answer != nullptr && model_tick_ >= 0 && answer->request_tick <= model_tick_) {
    ++counts_.outdated_answers;
    answer = nullptr;
  }
  if (answer != nullptr) {
    if (options_.blend && model_tick_ >= 0) {
      // What was rendered, at the current state, before the replacement.
      Evaluate(tool, tick, &scratch_);
      Wrench before = scratch_.wrench.w0;
      before.f_W += offset_.f_W;
      before.tau_W += offset_.tau_W;
      Accept(*answer, tick);
      Evaluate(tool, tick, &summary_);
      offset_.f_W = before.f_W - summary_.wrench.w0.f_W;
      offset_.tau_W = before.tau_W - summary_.wrench.w0.tau_W;
      const double n = std::ceil(std::max({1.0, offset_.f_W.norm() / options_.max_force_step,
                                           offset_.tau_W.norm() / options_.max_torque_step}));
      offset_ticks_left_ = std::min<int64_t>(static_cast<int64_t>(n), kMaxBlendTicks);
      offset_step_.f_W = offset_.f_W / static_cast<double>(offset_ticks_left_);
      offset_step_.tau_W = offset_.tau_W / static_cast<double>(offset_ticks_left_);
    } else {
      Accept(*answer, tick);
      Evaluate(tool, tick, &summary_);
    }
  } else {
    Evaluate(tool, tick, &summary_);
  }

  // The replacement offset steps toward zero, one step per tick.
  if (offset_ticks_left_ > 0) {
    offset_.f_W -= offset_step_.f_W;
    offset_.tau_W -= offset_step_.tau_W;
    if (--offset_ticks_left_ == 0) offset_ = Wrench{};
    summary_.wrench.w0.f_W += offset_.f_W;
    summary_.wrench.w0.tau_W += offset_.tau_W;
    ++counts_.blend_ticks;
  }

  // Ageing: a geometry thread that stalls lets the contact ramp out.
  const int64_t age = model_age(tick);
  if (age > options_.max_age_ticks) {
    const double over = static_cast<double>(age - options_.max_age_ticks);
    const double scale =
        std::max(0.0, 1.0 - over / static_cast<double>(std::max<int64_t>(options_.age_ramp_ticks, 1)));
    summary_.wrench.w0.f_W *= scale;
    summary_.wrench.w0.tau_W *= scale;
    summary_.wrench.K *= scale;
    summary_.wrench.D *= scale;
    *flags |= kFlagModelStale;
    ++counts_.stale_ticks;
  }
  if (summary_.num_invalid > 0) {
    *flags |= kFlagPdInvalid;
    if (summary_.num_held > 0) {
      *flags |= kFlagContactHeld;
      ++counts_.held_ticks;
    }
    if (summary_.num_held < summary_.num_invalid) ++counts_.dropped_ticks;
  }
  return summary_;
}

}  // namespace haptics
