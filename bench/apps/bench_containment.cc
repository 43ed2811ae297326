// bench_containment: what the collision test's containment part costs per
// query since it tests one vertex per connected component (issue 12), on the
// issue's two-part case, CGAL's many-part bones.off and the 52k-triangle
// closed armadillo.off, beside the old single-vertex test as a baseline in
// the same run.
//
//   bench_containment [--out DIR] [--mesh-dir DIR] [--repeats N]
//
// Per case (a probe and a scene at fixed poses): wall-clock times of
// InCollision (surface test + containment), of SurfacesIntersect alone, of
// the containment part (AnyComponentInside: one PointInsideMesh per
// component representative, both ways) and of the old test (vertex 0 of
// each mesh only), each repeated N times (median / p99 / max, microseconds).
// Writes containment_cost.md, .csv and .png (gnuplot) into --out (default
// bench/results).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bench/common/machine_info.h"
#include "bench/report/markdown_format.h"
#include "bench/common/stats.h"
#include "pd_core/mesh/load_mesh.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/point_in_mesh.h"
#include "pd_core/proximity/solid_containment.h"

#ifndef PD_SOURCE_DIR
#define PD_SOURCE_DIR "."
#endif

namespace {

namespace fs = std::filesystem;
using pd::CollisionModel;
using pd::Isometry3;
using pd::TriangleMesh;
using pd::Vector3;
using Model = std::shared_ptr<const CollisionModel>;
using Clock = std::chrono::steady_clock;

struct Case {
  std::string name;
  Model P, S;
  std::string note;  // what the answer is and why
};

struct Result {
  std::string name, note;
  int probe_triangles = 0, scene_triangles = 0, probe_parts = 0, scene_parts = 0;
  bool colliding = false, surfaces_cross = false, old_answer = false;
  pd_bench::Summary in_collision, surfaces, containment, old_containment;
};

template <typename F>
pd_bench::Summary Time(int repeats, F&& f) {
  std::vector<double> us;
  us.reserve(repeats);
  volatile bool sink = false;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    sink = f();
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  (void)sink;
  return pd_bench::Summarize(us);
}

Result Run(const Case& c, int repeats) {
  const Isometry3 I = Isometry3::Identity();
  const pd::ModelPair pair(*c.P, *c.S, I, I);
  const Vector3 zero = Vector3::Zero();
  // The test before issue 12: vertex 0 of each mesh only.
  auto old_containment = [&] {
    if (c.S->closed() && pd::PointInsideMesh(*c.S, pair.ProbeVertex(0, zero))) return true;
    return c.P->closed() && pd::PointInsideMesh(*c.P, c.S->mesh().vertices[0]);
  };
  Result r;
  r.name = c.name;
  r.note = c.note;
  r.probe_triangles = c.P->mesh().num_triangles();
  r.scene_triangles = c.S->mesh().num_triangles();
  r.probe_parts = static_cast<int>(c.P->component_vertices().size());
  r.scene_parts = static_cast<int>(c.S->component_vertices().size());
  r.colliding = pd::InCollision(pair, zero);
  r.surfaces_cross = pd::SurfacesIntersect(pair, zero);
  r.old_answer = pd::SurfacesIntersect(pair, zero) || old_containment();
  r.in_collision = Time(repeats, [&] { return pd::InCollision(pair, zero); });
  r.surfaces = Time(repeats, [&] { return pd::SurfacesIntersect(pair, zero); });
  r.containment = Time(repeats, [&] { return pd::AnyComponentInside(pair, zero); });
  r.old_containment = Time(repeats, old_containment);
  return r;
}

// A point of the model's root BVH box (so containment queries cast rays)
// inside (or outside) its solid, with a cube of half-size `clearance` around
// it clear of the surface: rejection sampling, decided by the exact winding
// number.
Vector3 SamplePoint(const CollisionModel& m, bool inside, double clearance, std::mt19937& rng) {
  const pd::BvhNode& root = m.bvh().nodes()[0];
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Vector3 p = root.center_M + root.R_MB * root.half_B.cwiseProduct(Vector3(U(rng), U(rng), U(rng)));
    Model cube = CollisionModel::Build(pd::TranslatedMesh(pd::MakeBox(Vector3::Constant(clearance)), p));
    if (pd::SurfacesIntersect(pd::ModelPair(*cube, m, Isometry3::Identity(), Isometry3::Identity()),
                              Vector3::Zero()))
      continue;
    if ((std::abs(pd::WindingNumber(m, p)) > 0.5) == inside) return p;
  }
  throw std::runtime_error("no sample point found in " + m.mesh().name);
}

Model Load(const std::string& path) {
  const pd::LoadedMesh loaded = pd::LoadMesh(path);
  return CollisionModel::Build(loaded.mesh);
}

void WriteReports(const std::vector<Result>& results, const pd_bench::MachineInfo& m, int repeats,
                  const fs::path& dir) {
  using pd_bench::F;
  fs::create_directories(dir);
  std::ofstream csv(dir / "containment_cost.csv");
  csv << "case,probe_triangles,probe_parts,scene_triangles,scene_parts,colliding,surfaces_cross,"
         "old_answer,repeats,in_collision_median_us,in_collision_p99_us,in_collision_max_us,"
         "surfaces_median_us,containment_median_us,containment_p99_us,containment_max_us,"
         "old_containment_median_us,old_containment_p99_us,containment_over_old_median\n";
  for (const Result& r : results)
    csv << '"' << r.name << "\"," << r.probe_triangles << "," << r.probe_parts << "," << r.scene_triangles
        << "," << r.scene_parts << "," << r.colliding << "," << r.surfaces_cross << "," << r.old_answer << ","
        << repeats << "," << r.in_collision.median << "," << r.in_collision.p99 << "," << r.in_collision.max
        << "," << r.surfaces.median << "," << r.containment.median << "," << r.containment.p99 << ","
        << r.containment.max << "," << r.old_containment.median << "," << r.old_containment.p99 << ","
        << r.containment.median / r.old_containment.median << "\n";
  std::ofstream md(dir / "containment_cost.md");
  md << "# Containment cost per collision test (issue 12)\n\n"
     << "Generated by `bench_containment` (bench/apps/bench_containment.cc); every number below was measured in "
        "this run.\n\n"
     << "- CPU: " << m.cpu_model << " (" << m.num_cpus << " logical CPUs), load average at the end "
     << pd_bench::ReadLoadAverage() << "\n- date " << m.date_utc << ", commit " << m.git_commit << ", build "
     << m.build_type << ", " << m.compiler << "\n\n"
     << "`InCollision` = `SurfacesIntersect` (BVH pair descent) || `AnyComponentInside` (one "
        "`PointInsideMesh` per connected component of each mesh against the other, closed, mesh: ray "
        "parity through the BVH, the first clean ray, leaning toward the nearest root-box face, "
        "decides). Old = the test before issue 12: vertex 0 of each mesh only (wrong on multi-part meshes: "
        "column \"old answer\"). Each call timed "
     << repeats << " times with a steady clock (single thread, shared 2-core machine); microseconds.\n\n"
     << "| case | probe tris / parts | scene tris / parts | colliding | surfaces cross | old answer | "
        "InCollision median | p99 | max | SurfacesIntersect median | containment median | p99 | max | "
        "old containment median | p99 | containment / old |\n"
     << "|---|---:|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Result& r : results)
    md << "| " << r.name << " | " << r.probe_triangles << " / " << r.probe_parts << " | " << r.scene_triangles
       << " / " << r.scene_parts << " | " << (r.colliding ? "yes" : "no") << " | "
       << (r.surfaces_cross ? "yes" : "no") << " | " << (r.old_answer ? "yes" : "no")
       << (r.old_answer != r.colliding ? " (wrong)" : "") << " | " << F(r.in_collision.median, 2) << " | "
       << F(r.in_collision.p99, 2) << " | " << F(r.in_collision.max, 1) << " | " << F(r.surfaces.median, 2)
       << " | " << F(r.containment.median, 2) << " | " << F(r.containment.p99, 2) << " | "
       << F(r.containment.max, 1) << " | " << F(r.old_containment.median, 2) << " | "
       << F(r.old_containment.p99, 2) << " | " << F(r.containment.median / r.old_containment.median, 2)
       << " |\n";
  md << "\nCases:\n\n";
  for (const Result& r : results) md << "- " << r.name << ": " << r.note << "\n";
}

// containment_cost.png through gnuplot (script with inline data kept beside
// it): per case, median and p99 of the containment part and of the old test.
void WritePlot(const std::vector<Result>& results, const fs::path& dir) {
  const fs::path script = dir / "containment_cost.gp";
  {
    std::ofstream gp(script);
    gp << "# Generated by bench_containment; run `gnuplot containment_cost.gp` in this directory.\n"
       << "$data << EOD\n";
    for (size_t i = 0; i < results.size(); ++i)
      gp << i << " \"" << results[i].name << "\" " << results[i].containment.median << " "
         << results[i].containment.p99 << " " << results[i].old_containment.median << " "
         << results[i].old_containment.p99 << "\n";
    gp << "EOD\n"
       << "set terminal pngcairo size 1200,700\nset output 'containment_cost.png'\n"
       << "set title 'Containment part of InCollision per call (us, log scale)'\n"
       << "set logscale y\nset ylabel 'microseconds'\nset grid ytics\nset key top left\n"
       << "set xtics rotate by 25 right font ',8'\nset bmargin 12\nset lmargin 22\nset rmargin 2\nset boxwidth 0.2\n"
       << "set style fill solid 0.8\n"
       << "plot $data using ($1-0.3):3:xtic(2) with boxes title 'per component: median', "
          "'' using ($1-0.1):4 with boxes title 'per component: p99', "
          "'' using ($1+0.1):5 with boxes title 'old (vertex 0 only): median', "
          "'' using ($1+0.3):6 with boxes title 'old: p99'\n";
  }
  const std::string cmd = "cd '" + dir.string() + "' && gnuplot containment_cost.gp";
  if (std::system(cmd.c_str()) != 0)
    std::cerr << "bench_containment: gnuplot failed or is missing; plot not written (" << script.string()
              << ")\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Cost of the per-component containment test in InCollision"};
  std::string out = std::string(PD_SOURCE_DIR) + "/bench/results";
  std::string mesh_dir = std::string(PD_SOURCE_DIR) + "/build/meshes";
  int repeats = 2000;
  app.add_option("--out", out, "output directory for containment_cost.md / .csv");
  app.add_option("--mesh-dir", mesh_dir, "where scripts/fetch_meshes.sh put bones.off and armadillo.off");
  app.add_option("--repeats", repeats, "timed calls per case and test")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  std::vector<Case> cases;
  const TriangleMesh small = pd::MakeBox(Vector3::Constant(0.01));
  const Model two_cubes =
      CollisionModel::Build(pd::JoinedMeshes(pd::TranslatedMesh(small, Vector3(0.1, 0, 0)), small));
  const Model cube = CollisionModel::Build(pd::MakeBox(Vector3::Constant(0.025)));
  cases.push_back({"two cubes (far part first) in a cube", two_cubes, cube,
                   "issue 12's case: the part at the origin wholly inside the 0.025 cube"});
  cases.push_back({"cube around one of two cubes", cube, two_cubes, "the same, roles swapped"});

  std::mt19937 rng(3);
  const std::string bones_path = mesh_dir + "/bones.off", armadillo_path = mesh_dir + "/armadillo.off";
  for (const std::string& p : {bones_path, armadillo_path}) {
    if (!fs::exists(p)) {
      std::cerr << "bench_containment: " << p << " missing (run scripts/fetch_meshes.sh)\n";
      return 1;
    }
  }
  const Model bones = Load(bones_path);
  const Model armadillo = Load(armadillo_path);
  for (const auto& [model, name] :
       {std::pair{bones, std::string("bones.off")}, std::pair{armadillo, std::string("armadillo.off")}}) {
    const double clearance = 0.01 * model->radius();
    const Vector3 in = SamplePoint(*model, true, clearance, rng);
    const Vector3 outside = SamplePoint(*model, false, clearance, rng);
    const Model inner =
        CollisionModel::Build(pd::TranslatedMesh(pd::MakeBox(Vector3::Constant(clearance)), in));
    const Model outer =
        CollisionModel::Build(pd::TranslatedMesh(pd::MakeBox(Vector3::Constant(clearance)), outside));
    cases.push_back({"small cube inside " + name, inner, model,
                     "a cube of 1% of the mesh's radius at a random point inside its solid (no contact)"});
    cases.push_back({"small cube near " + name + " (free)", outer, model,
                     "the same cube at a random point of the mesh's bounding box outside its solid"});
    cases.push_back(
        {name + " as probe around a small cube inside it", model, inner,
         "every part of the mesh tested against the cube, and the cube's vertex against the mesh"});
  }
  // The costly case: every part of a many-part probe inside the scene's root
  // box, so each is tested by rays through the scene's 52k-triangle BVH.
  {
    const double scale = 0.05 * armadillo->radius() / bones->radius();
    TriangleMesh small_bones = bones->mesh();
    const Vector3 c = bones->center();
    for (Vector3& v : small_bones.vertices) v = (v - c) * scale;
    const double r = bones->radius() * scale;
    for (bool inside : {false, true}) {
      const Vector3 p = SamplePoint(*armadillo, inside, 1.01 * r, rng);
      cases.push_back({std::string("bones.off (26 parts, 5% of its size) ") +
                           (inside ? "inside armadillo.off" : "in armadillo.off's box, free"),
                       CollisionModel::Build(pd::TranslatedMesh(small_bones, p)), armadillo,
                       inside ? "every bone inside the solid: the first part tested decides"
                              : "every bone outside the solid but inside its root box: 26 parts, "
                                "each decided by rays through the 52k-triangle BVH (the worst case)"});
    }
  }
  std::vector<Result> results;
  for (const Case& c : cases) {
    results.push_back(Run(c, repeats));
    const Result& r = results.back();
    std::cerr << r.name << ": InCollision median " << r.in_collision.median << " us, containment "
              << r.containment.median << " us (old " << r.old_containment.median << " us), colliding "
              << r.colliding << "\n";
  }
  WriteReports(results, pd_bench::ReadMachineInfo(PD_SOURCE_DIR), repeats, out);
  WritePlot(results, out);
  std::cerr << "wrote " << out << "/containment_cost.md, .csv and .png\n";
  return 0;
}
