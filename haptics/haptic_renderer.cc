#include "haptics/haptic_renderer.h"

#include <chrono>

namespace haptics {
namespace {

// Off the tick (geometry thread on or auto), a query that takes long stops
// at its budget with its best verified answer; the next one goes on from it.
// There, too, a query answers before it rebuilds its candidate list: the
// geometry thread rebuilds it after publishing the answer, until the next
// pose is posted (GeometryWorker::RunOnce).
pd::PolyDepthOptions GeometryOptions(const ContactConfig& contact, pd::PolyDepthOptions options) {
  if (contact.geometry_thread != GeometryThreadMode::kOff) {
    if (options.max_time_us <= 0.0) options.max_time_us = contact.geometry_budget_s * 1e6;
    options.defer_list_builds = true;
  }
  return options;
}

}  // namespace

HapticRenderer::HapticRenderer(const SceneConfig& config, const SceneModels& models,
                               const pd::PolyDepthOptions& pd_options)
    : dt_(1.0 / config.servo.rate_hz),
      validator_(config.device.workspace_min, config.device.workspace_max),
      velocity_(config.coupling.velocity_filter_hz),
      envelope_(config.servo.soft_engage_s, config.servo.watchdog_timeout_s,
                config.servo.watchdog_ramp_s),
      geometry_(models.tool, models.X_TG, models.objects, config.contact,
                GeometryOptions(config.contact, pd_options)),
      local_(geometry_.num_objects(), config.contact,
             MakeLocalContactOptions(config.contact, config.device.max_force_rate,
                                     config.device.max_torque_rate, dt_)),
      worker_(&geometry_),
      mode_(config.contact.geometry_thread),
      sync_budget_us_(config.contact.sync_budget * dt_ * 1e6),
      tool_(config.tool.mass, config.tool.I_T, config.tool.gravity_W),
      coupling_(config.coupling, config.device.max_force, config.device.max_torque),
      limiter_(config.device, dt_),
      contact_summary_(&no_contact_) {
  sync_answer_.Reserve(geometry_.num_objects());
}

bool HapticRenderer::wants_geometry_thread() const { return mode_ != GeometryThreadMode::kOff; }

void HapticRenderer::set_geometry_worker_running(bool running) {
  worker_running_ = running && wants_geometry_thread();
  // auto starts on the worker when PolyDepth (milliseconds when cold) is in the scene.
  async_ = worker_running_ &&
           (mode_ == GeometryThreadMode::kOn || geometry_.any_polydepth());
  local_.set_blend(async_);
  fit_answers_ = 0;
}

const ContactSummary& HapticRenderer::ContactAt(const RigidState& tool, int32_t* flags) {
  const int64_t tick = output_.tick;
  const ContactSnapshot* answer = nullptr;
  bool in_line = false;
  if (async_ && mode_ == GeometryThreadMode::kAuto && fit_answers_ >= static_cast<int64_t>(1.0 / dt_) &&
      worker_.idle() && !geometry_.any_polydepth()) {
    // auto: the worker's answers fit the budget again and it is idle (it
    // touches the geometry only after a new Post): back in the tick.
    async_ = false;
    local_.set_blend(false);
    ++switches_;
  }
  if (async_) {
    worker_.Post(tool.X_W, tick);
    answer = worker_.TakeAnswer();
    if (answer != nullptr) fit_answers_ = answer->query_us <= sync_budget_us_ ? fit_answers_ + 1 : 0;
    ++async_ticks_;
  } else {
    geometry_.Query(tool.X_W, tick, &sync_answer_);
    geometry_.PrepareNext();  // in the tick, what the thread would do after it
    answer = &sync_answer_;
    in_line = true;
    if (worker_running_ && mode_ == GeometryThreadMode::kAuto && sync_answer_.query_us > sync_budget_us_) {
      // Too slow for the tick: the next queries go to the worker.
      async_ = true;
      local_.set_blend(true);
      fit_answers_ = 0;
      ++switches_;
    }
  }
  const ContactSummary& summary = local_.Update(answer, tool, tick, flags);
  model_age_ = local_.model_age(tick);
  tick_work_ = in_line ? -1 : local_.last_update_terms();
  return summary;
}

const WrenchOutput& HapticRenderer::Tick(double t, const PoseSample* pose) {
  const auto t_start = std::chrono::steady_clock::now();
  tick_work_ = 0;
  bool was_engaged = envelope_.engaged();
  int32_t flags = 0;

  bool fresh = false;
  if (pose != nullptr && validator_.Accept(*pose)) {
    fresh = true;
    const PoseSample& good = validator_.last_good();
    if (was_engaged && good.session != output_.pose_session) {
      // Another device stream took over (pose_source_lock.h): engage afresh,
      // tool at its handle, force from zero.
      envelope_.Restart();
      was_engaged = false;
      ++source_changes_;
    }
    device_.X_W = Isometry3::Identity();
    device_.X_W.linear() = good.q_WD.toRotationMatrix();
    device_.X_W.translation() = good.p_WD;
    if (was_engaged) {
      velocity_.Update(good);
    } else {
      velocity_.Reset(good);
    }
    output_.pose_seq = good.seq;
    output_.pose_utime = good.utime;
    output_.pose_session = good.session;
  }
  if (!fresh) {
    flags |= kFlagStaleInput;
    ++stale_ticks_;
  }

  const double scale = envelope_.Update(t, fresh, &flags);
  ++output_.tick;
  if (!envelope_.engaged()) {
    // Nothing to render before the first valid pose.
    output_.wrench = limiter_.Apply(Wrench{}, 0.0, &flags);
    output_.penetration_depth = 0.0;
    output_.contact_count = 0;
    output_.flags = flags;
    output_.solver_time_us = 0.0;
    return output_;
  }
  if (!was_engaged) {
    tool_.Reset(device_.X_W);
    // Nothing was posted before the first pose: the worker is idle.
    if (!async_ || worker_.idle()) geometry_.ResetWarmStarts();
    local_.Reset();
  }
  // Stale beyond the watchdog: the handle's motion is unknown.
  if (envelope_.watchdog_active()) velocity_.Stop();
  device_.v_W = velocity_.v_W();
  device_.w_W = velocity_.w_W();

  contact_summary_ = &ContactAt(tool_.state(), &flags);
  if (contact_summary_->num_invalid > 0) ++pd_invalid_ticks_;
  LinearizedWrench on_tool = coupling_.Linearize(device_, tool_.state());
  on_tool += contact_summary_->wrench;
  tool_.Step(dt_, on_tool);

  output_.wrench = limiter_.Apply(coupling_.OnDevice(device_, tool_.state()), scale, &flags);
  output_.penetration_depth = contact_summary_->max_depth;
  output_.contact_count = contact_summary_->num_regions;
  output_.flags = flags;
  output_.solver_time_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t_start).count();
  return output_;
}

RendererCounts HapticRenderer::counts() const {
  RendererCounts c;
  c.ticks = output_.tick;
  c.poses_accepted = validator_.accepted();
  c.poses_rejected = validator_.rejections();
  c.stale_ticks = stale_ticks_;
  const LocalContactCounts& local = local_.counts();
  c.pd_invalid = local.invalid_answers;
  c.pd_invalid_ticks = pd_invalid_ticks_;
  c.pd_held_ticks = local.held_ticks;
  c.model_updates = local.updates;
  c.model_stale_ticks = local.stale_ticks;
  c.model_outdated_answers = local.outdated_answers;
  c.geometry_async_ticks = async_ticks_;
  c.geometry_switches = switches_;
  c.tool_nonfinite = tool_.nonfinite_steps();
  c.limiter = limiter_.counts();
  c.watchdog_trips = envelope_.watchdog_trips();
  c.source_changes = source_changes_;
  return c;
}

}  // namespace haptics
