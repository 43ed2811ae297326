// bench_scene_cost: what a scene costs per servo tick, in process.
//
//   bench_scene_cost [--out DIR] [--config-dir DIR] [--mesh-dir DIR] [--cycles N]
//
// Times PenaltyContact::Compute (broad phase + PD of every candidate pair +
// penalty wrench) per tick along the same contact trajectory, a tool pressed
// 4 mm into an object and lifted 10 mm clear, sliding and turning slightly,
// at 1 kHz, for:
//   (a) one object in contact: config/box_on_box.yaml (box on box, GJK/EPA);
//   (b) config/many_objects.yaml: the same block in contact among 80 more
//       objects and a table plane, all out of reach;
//   (b') the same with cull_margin = 1 m: the broad phase keeps every object
//       (what (b) would cost without it);
//   (c) a primitive pair: the box tool on a plane (closed form);
//   (d) a mesh on a plane: the spoon tool of spoon_in_cup on a plane (closed
//       form over the mesh's hull), and the bunny (75k triangles) if found;
//   (e) a general mesh pair for scale: the spoon tool on the cup (PolyDepth).
// Also times loading a large mesh's precomputation with and without the disk
// cache (pd_core/mesh/model_cache.h). Writes scene_cost.md, scene_cost.csv and
// model_cache.csv into --out (default bench/results).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "bench/common/machine_info.h"
#include "bench/report/markdown_format.h"
#include "bench/common/stats.h"
#include "haptics/scene/build_scene.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics/contact/penalty_wrench.h"
#include "pd_core/mesh/load_mesh.h"
#include "pd_core/mesh/model_cache.h"

#ifndef PD_SOURCE_DIR
#define PD_SOURCE_DIR "."
#endif

namespace {

namespace fs = std::filesystem;
using haptics::Isometry3;
using haptics::Quaternion;
using haptics::Vector3;

struct CaseResult {
  std::string id, name, pair;
  int objects = 0;
  int ticks = 0, contact_ticks = 0;
  double mean_candidates = 0.0;
  pd_bench::Summary all_us, contact_us;  // wall time per Compute
};

double Micros(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

// The tool pose at tick i: origin `contact_z` above the surface point it
// touches first; 2 s cycles from 10 mm above to 4 mm in, with a 3 mm slide
// and a 0.05 rad wobble.
haptics::RigidState TrajectoryPose(int i, double contact_z, const Vector3& xy) {
  const double t = 1e-3 * i;
  const double press = 0.5 - 0.5 * std::cos(M_PI * t);  // 0 -> 1 -> 0 every 2 s
  haptics::RigidState s;
  s.X_W.translation() = xy + Vector3(0.003 * std::sin(0.7 * t), 0.002 * std::cos(0.5 * t),
                                     contact_z + 0.010 - 0.014 * press);
  s.X_W.linear() = Eigen::AngleAxisd(0.05 * std::sin(0.9 * t), Vector3(1, 0.5, 0).normalized()).toRotationMatrix();
  s.v_W = Vector3(0, 0, -0.014 * 0.5 * M_PI * std::sin(M_PI * t));
  return s;
}

// Height of the tool origin at which the tool's lowest point is at z = top.
double ContactHeight(const haptics::SceneModels& m, double top) {
  return top - haptics::TightBoundingBoxInWorld(*m.tool, m.X_TG).min_W.z();
}

CaseResult RunCase(const std::string& id, const std::string& name, const haptics::SceneConfig& config,
                   double surface_z, const Vector3& xy, int cycles) {
  const haptics::SceneModels models = haptics::BuildSceneModels(config);
  haptics::PenaltyContact contact(models, config.contact);
  const double z0 = ContactHeight(models, surface_z);
  CaseResult r;
  r.id = id;
  r.name = name;
  r.objects = contact.num_objects();
  // The pair in contact (the first candidate that touches), for the table.
  const int warm = 2000, ticks = 2000 * cycles;
  std::vector<double> all, in_contact;
  all.reserve(ticks);
  in_contact.reserve(ticks);
  double candidates = 0.0;
  for (int i = 0; i < warm + ticks; ++i) {
    const haptics::RigidState tool = TrajectoryPose(i, z0, xy);
    const auto t0 = std::chrono::steady_clock::now();
    const haptics::ContactSummary& c = contact.Compute(tool);
    const double us = Micros(std::chrono::steady_clock::now() - t0);
    if (i < warm) continue;
    all.push_back(us);
    candidates += c.num_candidates;
    if (c.num_in_contact > 0) {
      in_contact.push_back(us);
      if (r.pair.empty()) {
        for (int k = 0; k < contact.num_objects(); ++k) {
          if (!contact.last_result(k).in_collision) continue;
          r.pair = models.tool->Describe() + " / " + contact.object(k).geometry->Describe() + " (" +
                   pd::PdMethodName(contact.solver(k).method()) + ")";
          break;
        }
      }
    }
  }
  r.ticks = ticks;
  r.contact_ticks = static_cast<int>(in_contact.size());
  r.mean_candidates = candidates / ticks;
  r.all_us = pd_bench::Summarize(all);
  r.contact_us = pd_bench::Summarize(in_contact);
  std::printf("%-4s %-46s objects %3d candidates %5.2f contact ticks %5d | all: median %7.1f p99 %7.1f us | "
              "contact: median %7.1f p99 %7.1f us\n",
              id.c_str(), name.c_str(), r.objects, r.mean_candidates, r.contact_ticks, r.all_us.median,
              r.all_us.p99, r.contact_us.median, r.contact_us.p99);
  std::fflush(stdout);
  return r;
}

struct CacheResult {
  std::string mesh;
  int triangles = 0;
  double build_ms = 0, miss_ms = 0, hit_ms = 0;  // no cache; first load (build + write); cached load
  uint64_t file_bytes = 0;
};

CacheResult TimeCache(const std::string& path) {
  CacheResult r;
  r.mesh = fs::path(path).filename().string();
  const pd::TriangleMesh mesh = pd::LoadMesh(path).mesh;
  r.triangles = mesh.num_triangles();
  const fs::path dir = fs::temp_directory_path() / ("bench_scene_cache_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  auto time_ms = [&](const std::string& cache_dir, pd::ModelCacheReport* report) {
    std::vector<double> ms;
    for (int k = 0; k < 3; ++k) {
      if (cache_dir.empty() || k == 0) fs::remove_all(dir);  // miss: each repeat starts empty
      const auto t0 = std::chrono::steady_clock::now();
      pd::BuildCollisionModelCached(mesh, cache_dir, report);
      ms.push_back(1e-3 * Micros(std::chrono::steady_clock::now() - t0));
    }
    return pd_bench::Percentile(ms, 50);
  };
  pd::ModelCacheReport report;
  r.build_ms = time_ms("", &report);
  std::vector<double> miss;
  for (int k = 0; k < 3; ++k) {
    fs::remove_all(dir);
    const auto t0 = std::chrono::steady_clock::now();
    pd::BuildCollisionModelCached(mesh, dir.string(), &report);
    miss.push_back(1e-3 * Micros(std::chrono::steady_clock::now() - t0));
  }
  r.miss_ms = pd_bench::Percentile(miss, 50);
  r.file_bytes = fs::file_size(report.path);
  std::vector<double> hit;
  for (int k = 0; k < 5; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    pd::BuildCollisionModelCached(mesh, dir.string(), &report);
    hit.push_back(1e-3 * Micros(std::chrono::steady_clock::now() - t0));
    if (report.outcome != pd::ModelCacheOutcome::kHit) std::fprintf(stderr, "cache: expected a hit\n");
  }
  r.hit_ms = pd_bench::Percentile(hit, 50);
  fs::remove_all(dir);
  std::printf("cache %-16s %6d triangles: build %.1f ms, first load (build + write) %.1f ms, cached load %.1f ms, "
              "file %.1f MB\n",
              r.mesh.c_str(), r.triangles, r.build_ms, r.miss_ms, r.hit_ms, r.file_bytes / 1e6);
  return r;
}

void WriteCsv(const std::vector<CaseResult>& cases, const std::vector<CacheResult>& cache, const fs::path& out) {
  std::ofstream csv(out / "scene_cost.csv");
  csv << "case,name,pair,objects,mean_candidates,ticks,contact_ticks,median_us,p90_us,p99_us,max_us,mean_us,"
         "contact_median_us,contact_p99_us\n";
  for (const CaseResult& c : cases)
    csv << c.id << ",\"" << c.name << "\",\"" << c.pair << "\"," << c.objects << "," << c.mean_candidates << ","
        << c.ticks << "," << c.contact_ticks << "," << c.all_us.median << "," << c.all_us.p90 << ","
        << c.all_us.p99 << "," << c.all_us.max << "," << c.all_us.mean << "," << c.contact_us.median << ","
        << c.contact_us.p99 << "\n";
  std::ofstream cc(out / "model_cache.csv");
  cc << "mesh,triangles,build_ms,first_load_ms,cached_load_ms,file_bytes\n";
  for (const CacheResult& c : cache)
    cc << c.mesh << "," << c.triangles << "," << c.build_ms << "," << c.miss_ms << "," << c.hit_ms << ","
       << c.file_bytes << "\n";
}

void WriteMarkdown(const std::vector<CaseResult>& cases, const std::vector<CacheResult>& cache,
                   const pd_bench::MachineInfo& m, int cycles, const fs::path& out) {
  using pd_bench::F;
  std::ofstream md(out / "scene_cost.md");
  md << "# Scene cost per servo tick\n\n"
     << "Generated by `bench_scene_cost` (bench/apps/bench_scene_cost.cc); every number below was measured in "
        "this run.\n\n"
     << pd_bench::MachineMarkdown(m) << "\n"
     << "What is timed: `PenaltyContact::Compute` (broad phase, PD of every candidate pair, penalty force and "
        "torque) per tick, wall clock, single thread, along the same trajectory in every case: the tool "
        "pressed from 10 mm above its object to 4 mm into it and back every 2 s ("
     << cycles << " cycles after a 2 s warm-up), sliding a few mm and turning by up to 0.05 rad. "
        "\"contact\" columns: only ticks with a verified contact.\n\n"
     << "| case | scene | pair in contact (method) | objects | mean candidates | median us | p90 us | "
        "p99 us | max us | contact median us | contact p99 us |\n"
     << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const CaseResult& c : cases)
    md << "| " << c.id << " | " << c.name << " | " << c.pair << " | " << c.objects << " | "
       << F(c.mean_candidates, 2) << " | " << F(c.all_us.median) << " | " << F(c.all_us.p90) << " | "
       << F(c.all_us.p99) << " | " << F(c.all_us.max) << " | " << F(c.contact_us.median) << " | "
       << F(c.contact_us.p99) << " |\n";
  const CaseResult* a = nullptr;
  const CaseResult* b = nullptr;
  const CaseResult* b_all = nullptr;
  for (const CaseResult& c : cases) {
    if (c.id == "a") a = &c;
    if (c.id == "b") b = &c;
    if (c.id == "b'") b_all = &c;
  }
  if (a && b) {
    md << "\n**Many objects vs one: (b)/(a) = " << F(b->all_us.median / a->all_us.median, 2)
       << " at the median, " << F(b->all_us.p99 / a->all_us.p99, 2) << " at p99** ("
       << b->objects << " objects, " << F(b->mean_candidates, 2) << " candidates per tick on average).";
    if (b_all)
      md << " Without the broad phase culling anything ((b'), every object a candidate) the same scene costs "
         << F(b_all->all_us.median / a->all_us.median, 1) << "x (a) at the median.";
    md << "\n";
  }
  if (!cache.empty()) {
    md << "\n## Mesh precomputation with and without the disk cache\n\n"
       << "`pd::BuildCollisionModelCached` (pd_core/mesh/model_cache.h), median of 3-5 runs: build without a cache, "
          "first load into an empty cache directory (build + write), and a cached load (read, checksum, "
          "checks, compare the mesh).\n\n"
       << "| mesh | triangles | build ms | first load ms | cached load ms | speed-up | file MB |\n"
       << "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const CacheResult& c : cache)
      md << "| " << c.mesh << " | " << c.triangles << " | " << F(c.build_ms) << " | " << F(c.miss_ms) << " | "
         << F(c.hit_ms) << " | " << F(c.build_ms / c.hit_ms, 1) << "x | " << F(c.file_bytes / 1e6, 1) << " |\n";
  }
  md << "\nFiles: scene_cost.csv (one row per case), model_cache.csv (one row per mesh).\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = std::string(PD_SOURCE_DIR) + "/bench/results";
  std::string config_dir = std::string(PD_SOURCE_DIR) + "/config";
  std::string mesh_dir = std::string(PD_SOURCE_DIR) + "/build/meshes";
  int cycles = 5;
  CLI::App app{"Per-tick cost of haptic scenes (broad phase + PD + wrench) and of loading with the model cache."};
  app.add_option("--out", out, "directory for scene_cost.md/.csv and model_cache.csv");
  app.add_option("--config-dir", config_dir, "the scenes (config/)");
  app.add_option("--mesh-dir", mesh_dir, "meshes from scripts/fetch_meshes.sh (bunny00.off, armadillo.off)");
  app.add_option("--cycles", cycles, "2 s press cycles timed per case")->check(CLI::Range(1, 1000));
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::warn);

  const std::string box_on_box = config_dir + "/box_on_box.yaml";
  std::vector<CaseResult> cases;
  try {
    // The block's top face is at z = 0 in box_on_box and many_objects.
    const haptics::SceneConfig one = haptics::LoadSceneConfig(box_on_box);
    cases.push_back(RunCase("a", "box_on_box (one object)", one, 0.0, Vector3::Zero(), cycles));
    haptics::SceneConfig many = haptics::LoadSceneConfig(config_dir + "/many_objects.yaml");
    cases.push_back(RunCase("b", "many_objects (the same block + 81)", many, 0.0, Vector3::Zero(), cycles));
    many.contact.cull_margin = 1.0;
    cases.push_back(RunCase("b'", "many_objects, cull_margin 1 m (no culling)", many, 0.0, Vector3::Zero(), cycles));

    haptics::SceneConfig plane = one;  // the box tool on a table plane at z = 0
    plane.objects.resize(1);
    plane.objects[0].name = "table";
    plane.objects[0].shape = {"objects[0].shape", haptics::PlaneShape{}};
    plane.objects[0].X_WS = Isometry3::Identity();
    cases.push_back(RunCase("c", "box tool on a plane", plane, 0.0, Vector3::Zero(), cycles));

    const haptics::SceneConfig spoon = haptics::LoadSceneConfig(config_dir + "/spoon_in_cup.yaml");
    haptics::SceneConfig spoon_plane = plane;
    spoon_plane.tool = spoon.tool;
    cases.push_back(RunCase("d", "spoon tool (mesh) on a plane", spoon_plane, 0.0, Vector3::Zero(), cycles));
    const std::string bunny = mesh_dir + "/bunny00.off";
    if (fs::is_regular_file(bunny)) {
      haptics::SceneConfig bunny_plane = plane;
      haptics::MeshFileShape file;
      file.path = bunny;
      file.scale = 0.07;  // bunny00.off is ~1 unit across: ~7 cm
      bunny_plane.tool.shape = {"tool.shape", file};
      cases.push_back(RunCase("d2", "bunny00 (75k triangles) on a plane", bunny_plane, 0.0, Vector3::Zero(), cycles));
    } else {
      std::printf("d2: %s missing (scripts/fetch_meshes.sh): skipped\n", bunny.c_str());
    }
    // The spoon in the cup: bowl down, pressed on the cup floor (top z = -0.055).
    haptics::SceneConfig cup = spoon;
    const double floor_z = -0.055;
    cup.tool.X_TG = Isometry3(Eigen::AngleAxisd(M_PI / 2, Vector3::UnitY())) * spoon.tool.X_TG;
    cases.push_back(RunCase("e", "spoon on the cup floor (PolyDepth)", cup, floor_z, Vector3::Zero(), cycles));
  } catch (const haptics::ConfigError& e) {
    std::fprintf(stderr, "bench_scene_cost: %s\n", e.what());
    return 1;
  }

  std::vector<CacheResult> cache;
  for (const char* name : {"bunny00.off", "armadillo.off"}) {
    const std::string path = mesh_dir + "/" + name;
    if (fs::is_regular_file(path)) {
      cache.push_back(TimeCache(path));
    } else {
      std::printf("cache: %s missing (scripts/fetch_meshes.sh): skipped\n", path.c_str());
    }
  }

  fs::create_directories(out);
  WriteCsv(cases, cache, out);
  WriteMarkdown(cases, cache, pd_bench::ReadMachineInfo(PD_SOURCE_DIR), cycles, out);
  std::printf("wrote %s/scene_cost.md, scene_cost.csv, model_cache.csv\n", out.c_str());
  return 0;
}
