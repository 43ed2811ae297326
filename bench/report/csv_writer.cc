#include "bench/report/csv_writer.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>
#include <stdexcept>

#include "bench/report/summaries.h"

namespace pd_bench {
namespace {

// Empty field for a value that was not measured.
std::string Num(double v) {
  if (std::isnan(v)) return "";
  std::ostringstream s;
  s << std::setprecision(9) << v;
  return s.str();
}

std::ofstream Open(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  return f;
}

// result.work: box + triangle tests by kind of query.
constexpr const char* kWorkColumns =
    "pd_work_collision,pd_work_localisation,pd_work_out_projection,pd_work_list_builds,"
    "pd_work_other";
void WriteWork(std::ostream& f, const pd::PenetrationResult::Work& w) {
  f << w.collision << ',' << w.localisation << ',' << w.out_projection << ',' << w.list_builds
    << ',' << w.other;
}

}  // namespace

std::vector<std::string> WriteCsvFiles(const BenchRun& run, const std::string& dir) {
  {
    std::ofstream f = Open(dir + "/pd_cases.csv");
    f << "pair,scenario,index,colliding,pd_valid,pd_verified_free,pd_depth_m,pd_time_us,"
         "pd_in_pocket,pd_iterations,pd_starts,pd_iterated_starts,pd_contacts,pd_initializer,pd_tx_m,pd_ty_m,pd_tz_m,"
         "ref_depth_m,ref_time_ms,ref_directions,ref_check_pd_free,ref_answer_free,pd_rel_error,"
         "fcl_convex_collide,fcl_convex_depth_m,fcl_convex_time_us,fcl_convex_rel_error,"
         "fcl_mesh_collide,fcl_mesh_depth_m,fcl_mesh_time_us,fcl_mesh_contacts,"
         "fcl_mesh_rel_error,pd_box_tests,pd_triangle_tests," << kWorkColumns
      << ",ref_check_depth_m,ref_check_directions\n";
    for (const PairResult& p : run.pairs)
      for (const ScenarioResult& s : p.scenarios)
        for (const CaseRecord& r : s.cases) {
          const double ref = r.has_ref ? r.ref.depth : kNaN;
          f << p.pair.name << ',' << ScenarioName(s.scenario) << ',' << r.c.index << ','
            << r.c.colliding << ',' << r.pd.valid << ',' << r.pd.verified_free << ','
            << Num(r.pd.depth) << ',' << Num(r.pd.time_us) << ',' << r.pd.in_pocket << ','
            << r.pd.iterations << ',' << r.pd.starts << ',' << r.pd.iterated_starts << ','
            << r.pd.contacts << ',' << r.pd.initializer << ',' << Num(r.pd.translation_W.x())
            << ',' << Num(r.pd.translation_W.y()) << ',' << Num(r.pd.translation_W.z()) << ',';
          if (r.has_ref)
            f << Num(r.ref.depth) << ',' << Num(r.ref.time_ms) << ',' << r.ref.directions << ','
              << r.ref.pd_answer_free << ',' << r.ref.ref_answer_free << ','
              << Num(RelativeError(r.pd.depth, ref)) << ',';
          else
            f << ",,,,,,";
          if (r.has_fcl)
            f << r.fcl.convex_collide << ',' << Num(r.fcl.convex_depth) << ','
              << Num(r.fcl.convex_time_us) << ',' << Num(RelativeError(r.fcl.convex_depth, ref))
              << ',' << r.fcl.mesh_collide << ',' << Num(r.fcl.mesh_depth) << ','
              << Num(r.fcl.mesh_time_us) << ',' << r.fcl.mesh_contacts << ','
              << Num(RelativeError(r.fcl.mesh_depth, ref)) << ',';
          else
            f << ",,,,,,,,,";
          f << Num(r.pd.box_tests) << ',' << Num(r.pd.triangle_tests) << ',';
          WriteWork(f, r.pd.work);
          if (r.has_ref_check)
            f << ',' << Num(r.ref_check.depth) << ',' << r.ref_check.directions << '\n';
          else
            f << ",,\n";
        }
  }
  {
    std::ofstream f = Open(dir + "/pd_sweep.csv");
    f << "pair,scenario,config,cases,median_us,p90_us,mean_iterations,valid_rate,ref_cases,"
         "mean_abs_rel_error,p95_abs_rel_error,signed_mean_rel_error\n";
    for (const SweepRow& r : run.sweep)
      f << r.pair << ',' << ScenarioName(r.scenario) << ',' << r.config << ',' << r.n << ','
        << Num(r.median_us) << ',' << Num(r.p90_us) << ',' << Num(r.mean_iterations) << ','
        << Num(r.valid_rate) << ',' << r.n_ref << ',' << Num(r.mean_abs_error) << ','
        << Num(r.p95_abs_error) << ',' << Num(r.signed_mean_error) << '\n';
  }
  {
    std::ofstream f = Open(dir + "/pd_models.csv");
    f << "model,source,scale_file_to_m,triangles,closed,build_ms,memory_bytes,bytes_per_triangle\n";
    for (const auto& m : run.models)
      f << m->name << ',' << m->source << ',' << Num(m->scale) << ',' << m->triangles << ','
        << m->closed << ',' << Num(m->build_ms) << ',' << m->memory_bytes << ','
        << Num(static_cast<double>(m->memory_bytes) / m->triangles) << '\n';
  }
  return {"pd_cases.csv", "pd_sweep.csv", "pd_models.csv"};
}

std::string WriteHapticCsv(const std::vector<HapticPairResult>& runs, const std::string& dir) {
  const std::string name = "pd_haptic.csv";
  std::ofstream f = Open(dir + "/" + name);
  f << "pair,index,colliding,pd_in_collision,pd_valid,pd_verified_free,pd_free_beyond,"
       "pd_converged,pd_depth_m,pd_time_us,pd_iterations,pd_contacts,pd_initializer,"
       "pd_box_tests,pd_triangle_tests,cold_restart,fcl_collide,fcl_time_us,ref_depth_m,"
       "pd_rel_error,cross_checked,prepare_us,prepare_box_tests,prepare_lists_completed,"
       "prepare_paused,inquery_in_collision,inquery_time_us,inquery_list_builds,"
       "inquery_list_build_us," << kWorkColumns
    << ",budget_converged,budget_free_beyond,budget_depth_m,budget_time_us,budget_rel_error,"
       "ref_directions\n";
  for (const HapticPairResult& r : runs)
    for (const HapticStep& s : r.steps) {
      f << r.spec.name << ',' << s.c.index << ',' << s.c.colliding << ',' << s.pd.in_collision
        << ',' << s.pd.valid << ',' << s.pd.verified_free << ',' << s.free_beyond << ','
        << s.converged << ',' << Num(s.pd.depth) << ',' << Num(s.pd.time_us) << ','
        << s.pd.iterations << ',' << s.pd.contacts << ',' << s.pd.initializer << ','
        << Num(s.box_tests) << ',' << Num(s.triangle_tests) << ',' << s.cold_restart << ','
        << s.fcl_collide << ',' << Num(s.fcl_time_us) << ','
        << (s.has_ref ? Num(s.ref.depth) : "") << ','
        << (s.has_ref ? Num(RelativeError(s.pd.depth, s.ref.depth)) : "") << ','
        << s.cross_checked << ',' << Num(s.prepare_us) << ',' << Num(s.prepare_box_tests) << ','
        << s.lists_completed << ',' << s.prepare_paused << ',' << s.inquery_in_collision << ','
        << Num(s.inquery_time_us) << ',' << s.list_builds << ',' << Num(s.list_build_us) << ',';
      WriteWork(f, s.pd.work);
      if (s.has_budget)
        f << ',' << s.budget_converged << ',' << s.budget_free << ',' << Num(s.budget_depth) << ','
          << Num(s.budget_time_us) << ','
          << (s.has_ref ? Num(RelativeError(s.budget_depth, s.ref.depth)) : "");
      else
        f << ",,,,,";
      f << ',' << (s.has_ref ? std::to_string(s.ref.directions) : "") << '\n';
    }
  return name;
}

std::string WriteHapticPathsCsv(const std::vector<HapticPairResult>& runs,
                                const std::string& dir) {
  const std::string name = "pd_haptic_paths.csv";
  std::ofstream f = Open(dir + "/" + name);
  f << "pair,path,path_seed,colliding,median_us,p99_us,max_us,max_cpu_us,max_work,cold_restarts,"
       "not_free,budget_median_us,budget_p99_us,budget_max_us,budget_max_cpu_us,budget_stopped,"
       "budget_not_free\n";
  auto row = [&](const std::string& pair, int path, const HapticPathRun& p) {
    const Summary t = Summarize(p.us), b = Summarize(p.budget_us);
    double max_work = 0.0;
    for (double w : p.work) max_work = std::max(max_work, w);
    f << pair << ',' << path << ',' << p.path_seed << ',' << t.n << ',' << Num(t.median) << ','
      << Num(t.p99) << ',' << Num(t.max) << ',' << Num(Max(p.cpu_us)) << ',' << Num(max_work)
      << ',' << p.cold_restarts << ',' << p.not_free << ',';
    if (b.n > 0)
      f << Num(b.median) << ',' << Num(b.p99) << ',' << Num(b.max) << ','
        << Num(Max(p.budget_cpu_us)) << ',' << p.budget_stopped << ',' << p.budget_not_free;
    else
      f << ",,,,,";
    f << '\n';
  };
  for (const HapticPairResult& r : runs) {
    row(r.spec.name, 0, FirstHapticPathRun(r));
    for (size_t k = 0; k < r.more_paths.size(); ++k)
      row(r.spec.name, static_cast<int>(k) + 1, r.more_paths[k]);
  }
  return name;
}

}  // namespace pd_bench
