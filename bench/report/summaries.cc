#include "bench/report/summaries.h"

#include <cmath>

namespace pd_bench {
namespace {

struct ErrorStats {
  int n = 0;
  Summary abs;
  double signed_mean = kNaN;
};

ErrorStats Errors(const std::vector<double>& signed_errors) {
  ErrorStats e;
  e.n = static_cast<int>(signed_errors.size());
  e.abs = pd_bench::Summarize(Abs(signed_errors));
  e.signed_mean = Mean(signed_errors);
  return e;
}

template <typename DepthOf, typename TimeOf, typename CollideOf>
BaselineSummary SummarizeBaseline(const ScenarioResult& s, DepthOf depth_of, TimeOf time_of,
                                  CollideOf collide_of) {
  BaselineSummary b;
  std::vector<double> times, pd_times, errors;
  for (const CaseRecord& r : s.cases) {
    if (!r.c.colliding || !r.has_fcl) continue;
    ++b.n;
    times.push_back(time_of(r));
    pd_times.push_back(r.pd.time_us);
    if (!collide_of(r)) ++b.n_no_collision;
    if (r.has_ref) {
      const double e = RelativeError(depth_of(r), r.ref.depth);
      if (!std::isnan(e)) errors.push_back(e);
    }
  }
  b.time_us = pd_bench::Summarize(times);
  b.time_ratio = b.time_us.median / Percentile(pd_times, 50);
  const ErrorStats e = Errors(errors);
  b.n_ref = e.n;
  b.abs_error = e.abs;
  b.signed_mean_error = e.signed_mean;
  return b;
}

}  // namespace

WorkShares SharesOf(const std::vector<pd::PenetrationResult::Work>& works) {
  double c = 0, l = 0, o = 0, b = 0, r = 0;
  for (const pd::PenetrationResult::Work& w : works) {
    c += w.collision;
    l += w.localisation;
    o += w.out_projection;
    b += w.list_builds;
    r += w.other;
  }
  const double all = c + l + o + b + r;
  if (!(all > 0)) return {};
  return {c / all, l / all, o / all, b / all, r / all};
}

double RelativeError(double depth, double ref) {
  if (!(ref > 0) || std::isnan(depth)) return kNaN;
  return (depth - ref) / ref;
}

ScenarioSummary Summarize(const ScenarioResult& s) {
  ScenarioSummary out;
  std::vector<double> starts, iterated_starts, boxes, triangles;
  std::vector<pd::PenetrationResult::Work> works;
  std::vector<double> times, iterations, contacts, errors, excess, ref_ms, ref_pd_us;
  std::vector<double> ref_over_check, error_on_check_cases, error_vs_check, check_ms;
  int valid = 0, verified = 0, ref_free = 0;
  for (const CaseRecord& r : s.cases) {
    if (!r.c.colliding) continue;
    ++out.n;
    times.push_back(r.pd.time_us);
    iterations.push_back(r.pd.iterations);
    starts.push_back(r.pd.starts);
    iterated_starts.push_back(r.pd.iterated_starts);
    boxes.push_back(r.pd.box_tests);
    triangles.push_back(r.pd.triangle_tests);
    works.push_back(r.pd.work);
    out.n_not_free_beyond += r.pd.verified_free && !r.pd.free_beyond;
    contacts.push_back(r.pd.contacts);
    valid += r.pd.valid;
    verified += r.pd.verified_free;
    out.n_invalid += !(r.pd.valid && r.pd.verified_free);
    out.n_pocket += r.pd.in_pocket;
    if (!r.has_ref) continue;
    ++out.n_ref;
    ref_free += r.ref.pd_answer_free;
    out.n_ref_not_free += !r.ref.ref_answer_free;
    ref_ms.push_back(r.ref.time_ms);
    ref_pd_us.push_back(r.pd.time_us);
    const double e = RelativeError(r.pd.depth, r.ref.depth);
    if (std::isnan(e)) continue;
    errors.push_back(e);
    excess.push_back(std::max(0.0, e));  // (d - min(d, ref)) / min(d, ref)
    if (e < 0) excess.back() = 0.0;
    out.n_below_ref += e < -1e-6;
    if (!r.has_ref_check || !(r.ref_check.depth > 0)) continue;
    ++out.n_ref_check;
    const double over = RelativeError(r.ref.depth, r.ref_check.depth);
    ref_over_check.push_back(over);
    out.n_check_below_ref += over > 1e-3;
    error_on_check_cases.push_back(std::abs(e));
    error_vs_check.push_back(std::abs(RelativeError(r.pd.depth, r.ref_check.depth)));
    check_ms.push_back(r.ref_check.time_ms);
  }
  out.time_us = pd_bench::Summarize(times);
  out.mean_iterations = Mean(iterations);
  out.mean_contacts = Mean(contacts);
  out.mean_starts = Mean(starts);
  out.mean_iterated_starts = Mean(iterated_starts);
  out.mean_box_tests = Mean(boxes);
  out.mean_triangle_tests = Mean(triangles);
  out.work = SharesOf(works);
  if (out.n > 0) {
    out.valid_rate = static_cast<double>(valid) / out.n;
    out.verified_rate = static_cast<double>(verified) / out.n;
  }
  if (out.n_ref > 0) out.ref_free_rate = static_cast<double>(ref_free) / out.n_ref;
  const ErrorStats e = Errors(errors);
  out.abs_error = e.abs;
  out.abs_error_mean_ci = BootstrapMeanInterval(Abs(errors));
  out.signed_mean_error = e.signed_mean;
  out.excess = pd_bench::Summarize(excess);
  out.ref_over_check = pd_bench::Summarize(ref_over_check);
  out.abs_error_on_check_cases = pd_bench::Summarize(error_on_check_cases);
  out.abs_error_vs_check = pd_bench::Summarize(error_vs_check);
  out.ref_check_time_ms = pd_bench::Summarize(check_ms);
  out.ref_time_ms = pd_bench::Summarize(ref_ms);
  out.ref_time_ratio = out.ref_time_ms.median * 1000.0 / Percentile(ref_pd_us, 50);
  out.fcl_convex = SummarizeBaseline(
      s, [](const CaseRecord& r) { return r.fcl.convex_depth; },
      [](const CaseRecord& r) { return r.fcl.convex_time_us; },
      [](const CaseRecord& r) { return r.fcl.convex_collide; });
  out.fcl_mesh = SummarizeBaseline(
      s, [](const CaseRecord& r) { return r.fcl.mesh_depth; },
      [](const CaseRecord& r) { return r.fcl.mesh_time_us; },
      [](const CaseRecord& r) { return r.fcl.mesh_collide; });
  return out;
}

SweepRow SummarizeOutcomes(const ScenarioResult& s, const std::vector<PdOutcome>& outcomes) {
  SweepRow row;
  row.scenario = s.scenario;
  std::vector<double> times, iterations, errors;
  int ok = 0;
  for (size_t i = 0; i < s.cases.size(); ++i) {
    const CaseRecord& r = s.cases[i];
    const PdOutcome& o = outcomes[i];
    if (!r.c.colliding || std::isnan(o.time_us)) continue;  // not solved in this row
    ++row.n;
    times.push_back(o.time_us);
    iterations.push_back(o.iterations);
    ok += o.valid && o.verified_free;
    if (r.has_ref) {
      const double e = RelativeError(o.depth, r.ref.depth);
      if (!std::isnan(e)) errors.push_back(e);
    }
  }
  row.median_us = Percentile(times, 50);
  row.p90_us = Percentile(times, 90);
  row.mean_iterations = Mean(iterations);
  if (row.n > 0) row.valid_rate = static_cast<double>(ok) / row.n;
  const ErrorStats e = Errors(errors);
  row.n_ref = e.n;
  row.mean_abs_error = e.abs.mean;
  row.p95_abs_error = e.abs.p95;
  row.signed_mean_error = e.signed_mean;
  return row;
}

}  // namespace pd_bench
