#include "bench/runs/knob_sweep.h"

#include <cstdio>
#include <initializer_list>

#include "bench/runs/pd_runner.h"
#include "bench/runs/reference_runner.h"
#include "bench/report/summaries.h"

namespace pd_bench {
namespace {

std::string Label(const char* knob, double value, const char* format = "%g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return std::string(knob) + "=" + buf;
}

bool Runs(const KnobConfig& k, Scenario s) {
  return k.coherent_scenarios ? s != Scenario::kRandom : s == Scenario::kRandom;
}

// A warm-started configuration depends on the previous step: it needs the path.
bool NeedsWholeSequence(const KnobConfig& k) {
  return k.coherent_scenarios && k.options.warm_start;
}

// Which cases of a scenario the sweep solves.
std::vector<bool> SweepMask(const ScenarioResult& s, int sweep_cases) {
  std::vector<bool> mask(s.cases.size(), false);
  std::vector<int> colliding;
  for (size_t i = 0; i < s.cases.size(); ++i) {
    if (!s.cases[i].c.colliding) continue;
    colliding.push_back(static_cast<int>(i));
    if (s.cases[i].has_ref) mask[i] = true;
  }
  for (int i : SpreadIndices(static_cast<int>(colliding.size()), sweep_cases))
    mask[colliding[i]] = true;
  return mask;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> SweptKnobDefaults() {
  const pd::PolyDepthOptions d;
  auto value = [](const std::string& label) { return label.substr(label.find('=') + 1); };
  return {{"max_iterations", value(Label("max_iterations", d.max_iterations))},
          {"convergence_tol", value(Label("convergence_tol", d.convergence_tol, "%.0e"))},
          {"num_maximally_clear", value(Label("num_maximally_clear", d.num_maximally_clear))},
          {"num_iterated_starts", value(Label("num_iterated_starts", d.num_iterated_starts))},
          {"cold_start_gate", value(Label("cold_start_gate", d.cold_start_gate, "%.2g"))},
          {"cold_shell_probes", value(Label("cold_shell_probes", d.cold_shell_probes))},
          {"num_random", value(Label("num_random", d.num_random))},
          {"cold_join", value(Label("cold_join", d.cold_join))},
          {"cold_screen_tol", value(Label("cold_screen_tol", d.cold_screen_tol, "%.0e"))},
          {"cold_inner_probes", value(Label("cold_inner_probes", d.cold_inner_probes))},
          {"cold_deep_probes", value(Label("cold_deep_probes", d.cold_deep_probes))},
          {"max_time_us", value(Label("max_time_us", d.max_time_us))}};
}

std::vector<KnobConfig> SweepConfigs() {
  const pd::PolyDepthOptions d;
  std::vector<KnobConfig> out;
  out.push_back({"default", d, false, true});
  // One knob varied over `values` (its default left out: the default row
  // stands for it), on the random scenario.
  auto sweep = [&](const char* knob, auto field, auto values, const char* format = "%g") {
    for (auto v : values) {
      if (v == d.*field) continue;
      KnobConfig k{Label(knob, v, format), d};
      k.options.*field = v;
      out.push_back(k);
    }
  };
  using O = pd::PolyDepthOptions;
  using Ints = std::initializer_list<int>;
  using Doubles = std::initializer_list<double>;
  sweep("max_iterations", &O::max_iterations, Ints{1, 2, 4, 8, 40});
  sweep("convergence_tol", &O::convergence_tol, Doubles{1e-3, 1e-4, 1e-5, 1e-6}, "%.0e");
  sweep("num_maximally_clear", &O::num_maximally_clear, Ints{8, 24, 48, 96, 128});
  sweep("num_iterated_starts", &O::num_iterated_starts, Ints{1, 2, 3, 4, 8});
  sweep("cold_start_gate", &O::cold_start_gate, Doubles{0.0, 0.03, 0.1, 1e300}, "%.2g");
  sweep("cold_shell_probes", &O::cold_shell_probes, Ints{0, 128, 256, 384});
  sweep("num_random", &O::num_random, Ints{0, 2, 4});
  // Speed for accuracy (off by default).
  sweep("cold_join", &O::cold_join, Doubles{0.0, 1e-2, 2e-2, 5e-2});
  sweep("cold_screen_tol", &O::cold_screen_tol, Doubles{0.0, 3e-4, 1e-3, 3e-3}, "%.0e");
  sweep("cold_inner_probes", &O::cold_inner_probes, Ints{0, 48});  // what the inner probes buy
  // Accuracy for speed (off by default).
  sweep("cold_deep_probes", &O::cold_deep_probes, Ints{0, 2});
  // Bounded time (PolyDepthOptions::max_time_us; unbounded by default): what
  // a caller who cannot wait gets from a cold query.
  sweep("max_time_us", &O::max_time_us, Doubles{0.0, 1000.0, 2000.0, 3000.0});
  // The same budgets iterating as many starts as an unbounded query (3, not
  // num_iterated_starts_bounded's 1): the same-run baseline for that default.
  for (double us : {1000.0, 2000.0, 3000.0}) {
    KnobConfig k{Label("max_time_us_3_iterated", us), d};
    k.options.max_time_us = us;
    k.options.num_iterated_starts_bounded = d.num_iterated_starts;
    out.push_back(k);
  }
  // A probe held still under a 1 ms budget after a cold query: what the
  // queries after it (which go on with the search the budget cut) answer
  // after 1, 3 and 10 of them. Times are the sum over the queries.
  for (int held : {1, 3, 10}) {
    KnobConfig k{Label("max_time_us_1000_held", held), d};
    k.options.max_time_us = 1000.0;
    k.held_queries = held;
    out.push_back(k);
  }
  out.push_back({"default", d, true, true});
  KnobConfig cold{"warm_start=off", d, true};
  cold.options.warm_start = false;
  out.push_back(cold);
  return out;
}

int SweepWork(const PairResult& pair, const std::vector<KnobConfig>& configs, int sweep_cases) {
  int work = 0;
  for (const KnobConfig& k : configs) {
    if (k.is_default) continue;
    for (const ScenarioResult& s : pair.scenarios) {
      if (!Runs(k, s.scenario)) continue;
      if (NeedsWholeSequence(k)) {
        work += static_cast<int>(s.cases.size());
        continue;
      }
      for (bool m : SweepMask(s, sweep_cases)) work += m;
    }
  }
  return work;
}

std::vector<SweepRow> RunSweep(const PairResult& pair, const std::vector<KnobConfig>& configs,
                               int sweep_cases, Progress* progress) {
  std::vector<SweepRow> rows;
  for (const KnobConfig& k : configs) {
    for (const ScenarioResult& s : pair.scenarios) {
      if (!Runs(k, s.scenario)) continue;
      const std::vector<bool> mask = SweepMask(s, sweep_cases);
      std::vector<PdOutcome> outcomes;
      if (k.is_default) {
        for (const CaseRecord& r : s.cases) outcomes.push_back(r.pd);
      } else if (NeedsWholeSequence(k)) {
        std::vector<Case> cases;
        for (const CaseRecord& r : s.cases) cases.push_back(r.c);
        outcomes = RunPolyDepth(pair.pair, cases, k.options, true, progress);
      } else {
        std::vector<Case> cases;
        for (size_t i = 0; i < s.cases.size(); ++i)
          if (mask[i]) cases.push_back(s.cases[i].c);
        const std::vector<PdOutcome> ran =
            k.held_queries > 0
                ? RunHeldPolyDepth(pair.pair, cases, k.options, k.held_queries, progress)
                : RunPolyDepth(pair.pair, cases, k.options, s.scenario != Scenario::kRandom,
                               progress);
        outcomes.resize(s.cases.size());
        for (size_t i = 0, j = 0; i < s.cases.size(); ++i)
          if (mask[i]) outcomes[i] = ran[j++];
      }
      // Same cases in every row: drop answers outside the mask.
      for (size_t i = 0; i < outcomes.size(); ++i)
        if (!mask[i]) outcomes[i].time_us = kNaN;
      SweepRow row = SummarizeOutcomes(s, outcomes);
      row.pair = pair.pair.name;
      row.config = k.label;
      if (const size_t eq = k.label.find('='); eq != std::string::npos) {
        row.knob = k.label.substr(0, eq);
        row.value = k.label.substr(eq + 1);
      }
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace pd_bench
