// bench_primitives: what each PD path of the dispatcher (pd_core/pair_pd_solver.h)
// costs and how accurate it is, against FCL 0.7's GJK/EPA on the same pairs.
//
//   bench_primitives [--out DIR] [--poses N] [--ref-poses N] [--seed N]
//
// Per pair: N random in-collision poses (probe centre within 0.8 x the sum of
// bounding radii of the scene's, random orientations; for a half-space, a
// random tilt and height), solved cold by PairPdSolver, timed with a steady
// clock around Solve (median / p90 / p99 / max). The same poses through
// fcl::collide (GST_LIBCCD, one contact, shapes as FCL primitives or
// fcl::Convex), timed the same way; FCL's depth is compared with ours (ours
// is a certified upper bound, so FCL below ours is an FCL underestimate
// whenever ours matches the reference). On --ref-poses of them the slow
// reference PD (pd_core/reference/reference_pd.h) on 2% circumscribed tessellations
// (exact for polytopes) gives the error of both. Writes primitives_pd.md and
// primitives_pd.csv into --out (default bench/results).
#include <CLI/CLI.hpp>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "bench/common/machine_info.h"
#include "bench/report/markdown_format.h"
#include "bench/common/stats.h"
#include "pd_core/geometry/make_shapes.h"
#include "pd_core/pair_pd_solver.h"
#include "pd_core/reference/reference_pd.h"
#include "pd_core/geometry/tessellate_geometry.h"

#ifndef PD_SOURCE_DIR
#define PD_SOURCE_DIR "."
#endif

namespace {

namespace fs = std::filesystem;
using pd::Geometry;
using pd::Isometry3;
using pd::Quaternion;
using pd::Vector3;
using G = std::shared_ptr<const Geometry>;
using Clock = std::chrono::steady_clock;

// FCL's geometry for ours (nullptr where FCL has no equivalent).
std::shared_ptr<fcl::CollisionGeometryd> ToFcl(const Geometry& g) {
  switch (g.kind()) {
    case pd::ShapeKind::kHalfSpace: return std::make_shared<fcl::Halfspaced>(Vector3::UnitZ(), 0.0);
    case pd::ShapeKind::kSphere: return std::make_shared<fcl::Sphered>(g.sphere().radius);
    case pd::ShapeKind::kBox: return std::make_shared<fcl::Boxd>(2.0 * g.box().half_extents);
    case pd::ShapeKind::kCylinder:
      return std::make_shared<fcl::Cylinderd>(g.cylinder().radius, 2.0 * g.cylinder().half_length);
    case pd::ShapeKind::kCapsule:
      return std::make_shared<fcl::Capsuled>(g.capsule().radius, 2.0 * g.capsule().half_length);
    case pd::ShapeKind::kConvexMesh: {
      const pd::TriangleMesh& m = g.model()->mesh();
      auto verts = std::make_shared<std::vector<fcl::Vector3d>>(m.vertices.begin(), m.vertices.end());
      auto faces = std::make_shared<std::vector<int>>();
      for (const auto& t : m.triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
      return std::make_shared<fcl::Convexd>(verts, m.num_triangles(), faces);
    }
    case pd::ShapeKind::kMesh: return nullptr;
  }
  return nullptr;
}

Quaternion RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  return Quaternion(N(rng), N(rng), N(rng), N(rng)).normalized();
}

Isometry3 Pose(const Vector3& p, const Quaternion& q) {
  Isometry3 X = Isometry3::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = p;
  return X;
}

struct PairCase {
  std::string name;
  G probe, scene;
};

struct PairResult {
  std::string name, method;
  int poses = 0, ref_poses = 0, fcl_poses = 0, fcl_misses = 0, invalid = 0, fallbacks = 0;
  int ref_violations = 0;      // |ours - reference| > tessellation error + 1e-6 x size
  int fcl_ref_violations = 0;  // the same for FCL
  pd_bench::Summary ours_us, fcl_us;
  double mean_iterations = 0.0;
  pd_bench::Summary ours_ref_rel;   // (ours - reference) / reference
  pd_bench::Summary fcl_ref_rel;    // |FCL - reference| / reference
  pd_bench::Summary fcl_ours_rel;   // |FCL - ours| / ours, all poses
  double tess_rel = 0.0;            // worst tessellation error / reference depth
};

PairResult RunPair(const PairCase& c, int num_poses, int num_ref, std::mt19937& rng) {
  PairResult out;
  out.name = c.name;
  pd::PairPdSolver solver(c.probe, c.scene);
  out.method = pd::PdMethodName(solver.method());
  const bool polydepth = solver.method() == pd::PdMethod::kPolyDepth;
  if (polydepth) num_poses = std::min(num_poses, 500);
  const double size = c.probe->radius() + (c.scene->bounded() ? c.scene->radius() : c.probe->radius());
  auto fcl_probe = ToFcl(*c.probe), fcl_scene = ToFcl(*c.scene);
  std::vector<double> ours_us, fcl_us, ours_ref, fcl_ref, fcl_ours;
  long iterations = 0;
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const pd::TriangleMesh probe_mesh = pd::TessellateGeometry(*c.probe, 0.02);
  const pd::TriangleMesh scene_mesh =
      c.scene->bounded() ? pd::TessellateGeometry(*c.scene, 0.02) : pd::MakeBox(Vector3::Constant(20 * size));
  const double tess = pd::TessellationError(*c.probe, probe_mesh) +
                      (c.scene->bounded() ? pd::TessellationError(*c.scene, scene_mesh) : 0.0);
  int attempts = 0;
  while (out.poses < num_poses && attempts < 50 * num_poses) {
    ++attempts;
    const Isometry3 X_WS = Pose(Vector3(U(rng), U(rng), U(rng)) * size, RandomRotation(rng));
    const double reach = 0.8 * size;
    const Vector3 offset = c.scene->bounded() ? Vector3(Vector3(U(rng), U(rng), U(rng)) * reach)
                                              : Vector3(X_WS.linear() * Vector3(U(rng), U(rng), 0.5 * U(rng)) * reach);
    const Isometry3 X_WP = Pose(X_WS.translation() + offset, RandomRotation(rng));
    const auto t0 = Clock::now();
    const pd::PenetrationResult r = solver.Solve(X_WP, X_WS);
    const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    if (!r.in_collision) continue;
    ++out.poses;
    ours_us.push_back(us);
    iterations += r.iterations;
    if (!r.valid) ++out.invalid;
    double fcl_depth = -1.0;
    if (fcl_probe && fcl_scene) {
      fcl::CollisionObjectd oP(fcl_probe, X_WP), oS(fcl_scene, X_WS);
      fcl::CollisionRequestd request(1, true);
      fcl::CollisionResultd result;
      const auto f0 = Clock::now();
      fcl::collide(&oP, &oS, request, result);
      fcl_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - f0).count());
      ++out.fcl_poses;
      if (result.isCollision()) {
        fcl_depth = std::abs(result.getContact(0).penetration_depth);
        // Ours without its back-off (separation_margin x size), on poses
        // deep enough for a relative difference to mean something.
        const double exact = r.depth - pd::PolyDepthOptions{}.separation_margin * size;
        if (exact >= 1e-3 * size) fcl_ours.push_back(std::abs(fcl_depth - exact) / exact);
      } else {
        ++out.fcl_misses;
      }
    }
    if (out.ref_poses < num_ref) {
      ++out.ref_poses;
      pd::ReferencePdOptions opt;
      opt.num_directions = 600;
      const Isometry3 X_WM = c.scene->bounded() ? X_WS : X_WS * Pose(Vector3(0, 0, -20 * size), Quaternion::Identity());
      const pd::ReferencePdResult ref =
          pd::ReferencePenetrationDepth(probe_mesh, X_WP, true, scene_mesh, X_WM, true, opt);
      if (ref.depth > 0) {
        const double bound = tess + 1e-6 * size;
        ours_ref.push_back((r.depth - ref.depth) / ref.depth);
        if (std::abs(r.depth - ref.depth) > bound) ++out.ref_violations;
        if (fcl_depth >= 0) fcl_ref.push_back(std::abs(fcl_depth - ref.depth) / ref.depth);
        if (fcl_depth >= 0 && std::abs(fcl_depth - ref.depth) > bound) ++out.fcl_ref_violations;
        out.tess_rel = std::max(out.tess_rel, tess / ref.depth);
      }
    }
  }
  out.fallbacks = static_cast<int>(solver.epa_fallbacks());
  out.ours_us = pd_bench::Summarize(ours_us);
  out.fcl_us = pd_bench::Summarize(fcl_us);
  out.mean_iterations = out.poses ? static_cast<double>(iterations) / out.poses : 0.0;
  out.ours_ref_rel = pd_bench::Summarize(pd_bench::Abs(ours_ref));
  out.fcl_ref_rel = pd_bench::Summarize(fcl_ref);
  out.fcl_ours_rel = pd_bench::Summarize(fcl_ours);
  return out;
}

void WriteReports(const std::vector<PairResult>& results, const pd_bench::MachineInfo& m, int poses,
                  int ref_poses, const fs::path& dir) {
  using pd_bench::F;
  using pd_bench::G;
  fs::create_directories(dir);
  std::ofstream csv(dir / "primitives_pd.csv");
  csv << "pair,method,poses,invalid,epa_fallbacks,mean_iterations,ours_median_us,ours_p90_us,ours_p99_us,"
         "ours_max_us,fcl_poses,fcl_misses,fcl_median_us,fcl_p90_us,fcl_p99_us,ref_poses,"
         "ours_vs_ref_median_rel,ours_vs_ref_max_rel,tess_max_rel,fcl_vs_ref_median_rel,fcl_vs_ref_max_rel,"
         "fcl_vs_ours_median_rel,fcl_vs_ours_p99_rel,fcl_vs_ours_max_rel,ours_outside_ref_bound,"
         "fcl_outside_ref_bound\n";
  for (const PairResult& r : results)
    csv << r.name << "," << r.method << "," << r.poses << "," << r.invalid << "," << r.fallbacks << ","
        << r.mean_iterations << "," << r.ours_us.median << "," << r.ours_us.p90 << "," << r.ours_us.p99 << ","
        << r.ours_us.max << "," << r.fcl_poses << "," << r.fcl_misses << "," << r.fcl_us.median << ","
        << r.fcl_us.p90 << "," << r.fcl_us.p99 << "," << r.ref_poses << "," << r.ours_ref_rel.median << ","
        << r.ours_ref_rel.max << "," << r.tess_rel << "," << r.fcl_ref_rel.median << "," << r.fcl_ref_rel.max
        << "," << r.fcl_ours_rel.median << "," << r.fcl_ours_rel.p99 << "," << r.fcl_ours_rel.max << ","
        << r.ref_violations << "," << r.fcl_ref_violations << "\n";

  std::ofstream md(dir / "primitives_pd.md");
  md << "# PD per path: closed form, GJK/EPA, PolyDepth\n\n"
     << "Generated by `bench_primitives` (bench/apps/bench_primitives.cc); every number below was measured in "
        "this run.\n\n"
     << "- CPU: " << m.cpu_model << " (" << m.num_cpus << " logical CPUs), load average at the end "
     << pd_bench::ReadLoadAverage() << "\n- date " << m.date_utc << ", commit " << m.git_commit << ", build "
     << m.build_type << ", " << m.compiler << "\n\n"
     << "Per pair: " << poses << " random in-collision poses (PolyDepth pairs: at most 500), solved cold by "
        "`PairPdSolver::Solve` (wall clock around the call, single thread, shared 2-core machine), and the "
        "same poses through `fcl::collide` (GST_LIBCCD, one contact; primitives as FCL primitives, convex "
        "meshes as `fcl::Convex`). Errors: on the first " << ref_poses << " poses of each pair, against the "
        "slow reference PD on circumscribed tessellations with 2% chord error (exact for polytopes: box, "
        "convex mesh); \"tess\" is the worst tessellation error relative to the depth, the reference's own "
        "uncertainty for curved shapes; \"outside bound\": compared poses where |answer - reference| exceeds "
        "that tessellation error + 1e-6 of the pair's size (a real error). \"invalid\": answers whose "
        "separation certificate failed.\n\n"
     << "| pair | method | poses | median us | p90 us | p99 us | mean iters | invalid | EPA fallbacks | "
        "|ours-ref|/ref median | max | tess | outside bound | FCL median us | FCL p99 us | FCL/ours time | "
        "|FCL-ref|/ref median | max | FCL outside bound | |FCL-ours|/ours p99 | max | FCL misses |\n"
     << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const PairResult& r : results)
    md << "| " << r.name << " | " << r.method << " | " << r.poses << " | " << F(r.ours_us.median, 2) << " | "
       << F(r.ours_us.p90, 2) << " | " << F(r.ours_us.p99, 2) << " | " << F(r.mean_iterations, 1) << " | "
       << r.invalid << " | " << r.fallbacks << " | " << G(r.ours_ref_rel.median) << " | "
       << G(r.ours_ref_rel.max) << " | " << G(r.tess_rel) << " | " << r.ref_violations << "/" << r.ref_poses
       << " | " << F(r.fcl_us.median, 2) << " | "
       << F(r.fcl_us.p99, 2) << " | " << F(r.fcl_us.median / r.ours_us.median, 2) << " | "
       << G(r.fcl_ref_rel.median) << " | " << G(r.fcl_ref_rel.max) << " | "
       << (r.fcl_poses ? std::to_string(r.fcl_ref_violations) : "-") << " | " << G(r.fcl_ours_rel.p99) << " | "
       << G(r.fcl_ours_rel.max) << " | " << (r.fcl_poses ? std::to_string(r.fcl_misses) : "-") << " |\n";
  md << "\nReading the table: ours is a certified upper bound (a separating plane at the answer), so where "
        "|ours-ref| is at the reference's accuracy (1e-9 or below for polytopes; below \"tess\" for curved "
        "shapes) any larger |FCL-ours| is FCL's error (|FCL-ours|/ours: ours without its 1e-8 x size back-off, "
        "over poses deeper than 1e-3 x size). FCL misses: poses where FCL reports no collision "
        "though the shapes overlap by our certified depth.\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time and error of each PD path (closed form, GJK/EPA, PolyDepth) against FCL GJK/EPA"};
  std::string out = std::string(PD_SOURCE_DIR) + "/bench/results";
  int poses = 10000, ref_poses = 20;
  unsigned seed = 7;
  app.add_option("--out", out, "output directory for primitives_pd.md / .csv");
  app.add_option("--poses", poses, "in-collision poses per pair")->check(CLI::PositiveNumber);
  app.add_option("--ref-poses", ref_poses, "poses per pair compared with the reference PD")->check(CLI::NonNegativeNumber);
  app.add_option("--seed", seed, "random seed");
  CLI11_PARSE(app, argc, argv);

  const G plane = Geometry::MakeHalfSpace();
  const G sphere = Geometry::MakeSphere(0.05), sphere2 = Geometry::MakeSphere(0.04);
  const G box = Geometry::MakeBox(Vector3(0.06, 0.04, 0.03)), box2 = Geometry::MakeBox(Vector3(0.05, 0.05, 0.02));
  const G capsule = Geometry::MakeCapsule(0.02, 0.04), capsule2 = Geometry::MakeCapsule(0.03, 0.03);
  const G cylinder = Geometry::MakeCylinder(0.04, 0.05), cylinder2 = Geometry::MakeCylinder(0.03, 0.04);
  const G hull = Geometry::MakeConvexMesh(pd::CollisionModel::Build(pd::MakeIcosphere(0.05, 2)));
  const G box_mesh = Geometry::MakeConvexMesh(pd::CollisionModel::Build(pd::MakeBox(Vector3(0.05, 0.04, 0.03))));
  const G spoon = Geometry::MakeMesh(pd::CollisionModel::Build(pd::MakeSpoon(pd::SpoonDimensions{})));
  const G lrod = Geometry::MakeMesh(pd::CollisionModel::Build(pd::MakeLRod(0.07, 0.06, 0.03, 0.03)));
  const std::vector<PairCase> cases = {
      {"sphere-sphere", sphere, sphere2},     {"sphere-plane", sphere, plane},
      {"box-plane", box, plane},              {"cylinder-plane", cylinder, plane},
      {"capsule-plane", capsule, plane},      {"spoon mesh-plane", spoon, plane},
      {"sphere-box", sphere, box},            {"sphere-capsule", sphere, capsule},
      {"capsule-capsule", capsule, capsule2}, {"box-box", box, box2},
      {"capsule-box", capsule, box},          {"cylinder-box", cylinder, box},
      {"sphere-cylinder", sphere, cylinder},  {"cylinder-cylinder", cylinder, cylinder2},
      {"convex mesh (icosphere 320)-box mesh", hull, box_mesh},
      {"convex mesh-convex mesh", hull, hull}, {"L-rod mesh-box", lrod, box},
      {"L-rod mesh-sphere", lrod, sphere}};
  std::mt19937 rng(seed);
  std::vector<PairResult> results;
  for (const PairCase& c : cases) {
    results.push_back(RunPair(c, poses, ref_poses, rng));
    const PairResult& r = results.back();
    std::cerr << r.name << " (" << r.method << "): median " << r.ours_us.median << " us, FCL "
              << r.fcl_us.median << " us, |ours-ref|/ref max " << r.ours_ref_rel.max << "\n";
  }
  WriteReports(results, pd_bench::ReadMachineInfo(PD_SOURCE_DIR), poses, ref_poses, out);
  std::cerr << "wrote " << out << "/primitives_pd.md and primitives_pd.csv\n";
  return 0;
}
