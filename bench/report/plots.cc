#include "bench/report/plots.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "bench/runs/knob_sweep.h"
#include "bench/common/stats.h"

namespace pd_bench {
namespace {

// Log axes cannot show a zero error.
constexpr double kErrorFloorPct = 1e-3;

struct SweepPoint {
  double time_us, error_pct;
  std::string label;
  double order;  // position along the curve
};

// Writes a gnuplot datablock: time, error, label.
void Block(std::ostream& gp, const std::string& name, std::vector<SweepPoint> pts) {
  std::sort(pts.begin(), pts.end(),
            [](const SweepPoint& a, const SweepPoint& b) { return a.order < b.order; });
  gp << name << " << EOD\n";
  for (const SweepPoint& p : pts)
    gp << p.time_us << " " << std::max(p.error_pct, kErrorFloorPct) << " \"" << p.label << "\"\n";
  gp << "EOD\n";
}

SweepPoint Point(const SweepRow& r, const std::string& label, double order) {
  return {r.median_us, 100 * r.mean_abs_error, label, order};
}

// Where a knob's value sits along its curve: a time budget of 0 is none
// (the slowest end).
double KnobOrder(const std::string& knob, const std::string& value) {
  const double v = std::stod(value);
  return knob == "max_time_us" && v <= 0.0 ? 1e300 : v;
}

bool Plottable(const SweepRow& r) {
  return !std::isnan(r.median_us) && !std::isnan(r.mean_abs_error);
}

// Knob sweep: one panel per pair, x = median solve time, y = mean |error|;
// one curve per knob (through the defaults), and warm start on/off per path.
void SweepPlot(const BenchRun& run, std::ostream& gp) {
  const int n = static_cast<int>(run.pairs.size());
  const int cols = n > 1 ? 2 : 1, rows = (n + cols - 1) / cols;
  const auto knobs = SweptKnobDefaults();
  const char* colour[] = {"#1f77b4", "#ff7f0e", "#9467bd", "#8c564b",
                          "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#aec7e8", "#393b79"};
  const size_t num_colours = sizeof(colour) / sizeof(colour[0]);
  gp << "set terminal pngcairo size " << 900 * cols << "," << 600 * rows
     << " font 'DejaVu Sans,10'\n"
     << "set output 'pd_sweep_time_error.png'\n"
     << "set multiplot layout " << rows << "," << cols
     << " title 'PolyDepth knob sweep: median solve time vs mean |relative error| against the "
        "reference PD (one knob varied at a time; labels are its values)'\n"
     << "set logscale xy\nset grid\nset key below horizontal noenhanced\n"
     << "set xlabel 'median solve time (us, log)'\n"
     << "set ylabel 'mean |error| (%, log; < " << kErrorFloorPct << "% drawn at it)'\n";
  for (const PairResult& p : run.pairs) {
    std::vector<std::string> plots;
    const std::string id = p.pair.name;
    for (size_t k = 0; k < knobs.size(); ++k) {
      std::vector<SweepPoint> pts;
      for (const SweepRow& r : run.sweep) {
        if (r.pair != id || r.scenario != Scenario::kRandom || !Plottable(r)) continue;
        if (r.knob == knobs[k].first) pts.push_back(Point(r, r.value, KnobOrder(r.knob, r.value)));
        if (r.knob.empty())
          pts.push_back(Point(r, knobs[k].second, KnobOrder(knobs[k].first, knobs[k].second)));
      }
      if (pts.empty()) continue;
      const std::string block = "$s_" + id + "_" + std::to_string(k);
      Block(gp, block, pts);
      plots.push_back(block + " using 1:2 with linespoints pt 7 ps 1.1 lw 1.5 lc rgb '" +
                      colour[k % num_colours] + "' title 'random: " + knobs[k].first + "'");
      plots.push_back(block + " using 1:2:3 with labels font ',8' offset 0.8,0.6 left tc rgb '" +
                      colour[k % num_colours] + "' notitle");
    }
    for (Scenario sc : {Scenario::kPath, Scenario::kShallow}) {
      std::vector<SweepPoint> pts;
      for (const SweepRow& r : run.sweep)
        if (r.pair == id && r.scenario == sc && Plottable(r))
          pts.push_back(Point(r, r.knob.empty() ? "warm on" : "warm off", r.knob.empty() ? 0 : 1));
      if (pts.empty()) continue;
      const std::string name = ScenarioName(sc);
      const std::string block = "$s_" + id + "_" + name;
      const std::string c = sc == Scenario::kPath ? "#d62728" : "#2ca02c";
      Block(gp, block, pts);
      plots.push_back(block + " using 1:2 with linespoints pt 5 ps 1.3 dt 2 lw 1.5 lc rgb '" + c +
                      "' title '" + name + " (coherent): warm_start'");
      plots.push_back(block + " using 1:2:3 with labels font ',8' offset 0.8,-0.8 left tc rgb '" +
                      c + "' notitle");
    }
    gp << "set title '" << id << " (" << p.pair.probe->triangles << " vs "
       << p.pair.scene->triangles << " triangles)' noenhanced\n";
    gp << "plot ";
    for (size_t i = 0; i < plots.size(); ++i) gp << (i ? ", " : "") << plots[i];
    if (plots.empty()) gp << "NaN notitle";
    gp << "\n";
  }
  gp << "unset multiplot\n";
}

// Empirical CDF of solve time per pair, one panel per scenario.
void TimePlot(const BenchRun& run, std::ostream& gp) {
  gp << "reset\nset terminal pngcairo size 1800,560 font 'DejaVu Sans,10'\n"
     << "set output 'pd_time_distribution.png'\n"
     << "set multiplot layout 1,3 title 'PolyDepth solve time distribution (colliding cases, "
        "default options)'\n"
     << "set logscale x\nset grid\nset key bottom right noenhanced\n"
     << "set xlabel 'solve time (us, log)'\nset ylabel 'fraction of queries'\n"
     << "set yrange [0:1]\n";
  for (const char* scen : {"random", "path", "shallow"}) {
    std::vector<std::string> names;
    for (const PairResult& p : run.pairs) {
      std::vector<double> t;
      for (const ScenarioResult& s : p.scenarios)
        if (ScenarioName(s.scenario) == std::string(scen))
          for (const CaseRecord& r : s.cases)
            if (r.c.colliding) t.push_back(r.pd.time_us);
      if (t.empty()) continue;
      std::sort(t.begin(), t.end());
      const std::string data = "$t_" + p.pair.name + "_" + scen;
      gp << data << " << EOD\n";
      for (size_t i = 0; i < t.size(); ++i) gp << t[i] << " " << (i + 1.0) / t.size() << "\n";
      gp << "EOD\n";
      names.push_back(p.pair.name);
    }
    gp << "set title '" << scen
       << (std::string(scen) == "random" ? " (cold)" : " (coherent)") << "'\n";
    gp << "plot ";
    for (size_t i = 0; i < names.size(); ++i)
      gp << (i ? ", " : "") << "$t_" << names[i] << "_" << scen
         << " using 1:2 with steps lw 2 title '" << names[i] << "'";
    if (names.empty()) gp << "NaN notitle";
    gp << "\n";
  }
  gp << "unset multiplot\n";
}

// Empirical CDF of warm-query time on each haptic path, PolyDepth's answers
// (solid; list rebuilds deferred) against FCL's boolean collide at the same
// poses (dashed) and PolyDepth with the rebuilds in the queries (dotted).
void HapticPlot(const BenchRun& run, std::ostream& gp) {
  gp << "reset\nset terminal pngcairo size 1200,700 font 'DejaVu Sans,10'\n"
     << "set output 'pd_haptic_time.png'\n"
     << "set title 'Haptic paths: warm PolyDepth answers (solid; dotted: list rebuilds in the "
        "query) vs FCL boolean collide (dashed), colliding poses'\n"
     << "set logscale x\nset grid\nset key bottom right noenhanced\n"
     << "set xlabel 'time per query (us, log)'\nset ylabel 'fraction of queries'\n"
     << "set yrange [0:1]\n";
  std::vector<std::string> plots;
  int color = 1;
  for (const HapticPairResult& r : run.haptic) {
    std::vector<double> pd_t, fcl_t, inquery_t;
    for (const HapticStep& s : r.steps) {
      if (s.pd.in_collision) pd_t.push_back(s.pd.time_us), fcl_t.push_back(s.fcl_time_us);
      if (s.inquery_in_collision) inquery_t.push_back(s.inquery_time_us);
    }
    if (pd_t.empty()) continue;
    for (auto* t : {&pd_t, &fcl_t, &inquery_t}) {
      std::sort(t->begin(), t->end());
      const std::string data = std::string("$h_") +
                               (t == &pd_t ? "pd_" : t == &fcl_t ? "fcl_" : "inq_") + r.spec.name;
      gp << data << " << EOD\n";
      for (size_t i = 0; i < t->size(); ++i) gp << (*t)[i] << " " << (i + 1.0) / t->size() << "\n";
      gp << "EOD\n";
    }
    plots.push_back("$h_pd_" + r.spec.name + " using 1:2 with steps lw 2 lc " +
                    std::to_string(color) + " title '" + r.spec.name + "'");
    plots.push_back("$h_fcl_" + r.spec.name + " using 1:2 with steps lw 1 dt 2 lc " +
                    std::to_string(color) + " notitle");
    if (!inquery_t.empty())
      plots.push_back("$h_inq_" + r.spec.name + " using 1:2 with steps lw 1 dt 3 lc " +
                      std::to_string(color) + " notitle");
    ++color;
  }
  gp << "plot ";
  for (size_t i = 0; i < plots.size(); ++i) gp << (i ? ", " : "") << plots[i];
  if (plots.empty()) gp << "NaN notitle";
  gp << "\n";
}

}  // namespace

std::vector<std::string> WritePlots(const BenchRun& run, const std::string& dir) {
  if (run.pairs.empty() && run.haptic.empty()) return {};
  const std::string script = dir + "/pd_plots.gp";
  std::vector<std::string> pngs;
  {
    std::ofstream gp(script);
    gp << "# Generated by bench_pd; run `gnuplot pd_plots.gp` in this directory.\n";
    if (!run.pairs.empty()) {
      SweepPlot(run, gp);
      TimePlot(run, gp);
      pngs = {"pd_sweep_time_error.png", "pd_time_distribution.png"};
    }
    if (!run.haptic.empty()) {
      HapticPlot(run, gp);
      pngs.push_back("pd_haptic_time.png");
    }
  }
  const std::string cmd = "cd '" + dir + "' && gnuplot pd_plots.gp";
  if (std::system(cmd.c_str()) != 0) {
    std::cerr << "bench_pd: gnuplot failed or is missing; plots not written (" << script << ")\n";
    return {};
  }
  return pngs;
}

}  // namespace pd_bench
