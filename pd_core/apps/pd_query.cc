// pd_query: penetration depth of a probe mesh against a scene mesh for probe
// poses read from stdin, one JSON answer per line on stdout.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pd_core/mesh/collision_model.h"
#include "pd_core/mesh/load_mesh.h"
#include "pd_core/geometry/parse_pose_line.h"
#include "pd_core/polydepth/penetration_result.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_build/build_info.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitMeshError = 1;
constexpr int kExitBadLine = 2;
constexpr int kExitUsage = 3;

constexpr const char* kFooter = R"(
Input (stdin): one probe pose per line,
  x y z qw qx qy qz
the position of the probe frame P in world W (metres) and the unit quaternion
of its orientation, w first, separated by spaces or tabs. Mesh coordinates
(times the scale) are metres in each mesh's own frame; the probe mesh is
placed at X_WP, the scene mesh at X_WS (--scene-pose, default identity).
Blank lines and lines starting with # are skipped.

Output (stdout): one JSON object per pose line, in order:
  {"collision", "valid", "depth", "translation": [x,y,z], "normal": [x,y,z],
   "iterations", "contacts", "regions": [{"point", "normal", "local_depth"}],
   "initializer", "converged", "list_builds", "list_build_us", "starts",
   "iterated_starts", "cold_probes_resumed", "box_tests", "triangle_tests",
   "time_us"}
all vectors in W, lengths in metres; translation moves the probe out of
collision; time_us is solver time only; starts, box_tests and triangle_tests
are the query's cold starts and work (machine-independent cost);
iterated_starts the starts it iterated (searches of the contact space); converged
is false when --max-work or --max-time-us stopped the search early (the
answer is still verified free); cold_probes_resumed is true on a --coherent
line that went on with what such a budget cut from an earlier line's cold
search (its starts and probes; the following lines go on until it is done);
list_builds counts the --coherent query's rebuilds of its list of leaf pairs
near the contact (0 when cold), list_build_us is their share of time_us. A malformed line (wrong number of
fields, not a number, NaN/inf, quaternion norm not within 1e-3 of 1) gives
{"error": "line N: ..."} with N counting every input line from 1, and the
following lines are still answered.

Exit codes: 0 all lines answered, 1 a mesh cannot be loaded, 2 at least one
line was malformed or failed, 3 invalid command line.)";

nlohmann::ordered_json ToJson(const pd::Vector3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::ordered_json ToJson(const pd::PenetrationResult& r) {
  nlohmann::ordered_json regions = nlohmann::ordered_json::array();
  for (int i = 0; i < r.num_regions; ++i) {
    const pd::ContactRegion& region = r.regions[i];
    regions.push_back({{"point", ToJson(region.p_W)},
                       {"normal", ToJson(region.n_W)},
                       {"local_depth", region.local_depth}});
  }
  return {{"collision", r.in_collision},
          {"valid", r.valid},
          {"depth", r.depth},
          {"translation", ToJson(r.translation_W)},
          {"normal", ToJson(r.normal_W)},
          {"iterations", r.iterations},
          {"contacts", r.num_contacts},
          {"regions", regions},
          {"initializer", pd::InitializerName(r.initializer)},
          {"converged", r.converged},
          {"list_builds", r.list_builds},
          {"list_build_us", r.list_build_us},
          {"starts", r.starts},
          {"iterated_starts", r.iterated_starts},
          {"cold_probes_resumed", r.cold_probes_resumed},
          {"box_tests", r.box_tests},
          {"triangle_tests", r.triangle_tests},
          {"time_us", r.time_us}};
}

// Loads and builds one model; prints warnings; nullptr (message printed) on failure.
std::shared_ptr<const pd::CollisionModel> LoadModel(const std::string& path, double scale) {
  pd::MeshLoadOptions options;
  options.scale = scale;
  try {
    pd::LoadedMesh loaded = pd::LoadMesh(path, options);
    for (const std::string& w : loaded.warnings) std::cerr << "pd_query: warning: " << w << "\n";
    return pd::CollisionModel::Build(std::move(loaded.mesh));
  } catch (const pd::MeshLoadError& e) {
    std::cerr << "pd_query: " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "pd_query: " << path << ": cannot build collision model: " << e.what() << "\n";
  }
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Penetration depth (PolyDepth) of PROBE_MESH against SCENE_MESH for each probe "
               "pose read from stdin."};
  app.footer(kFooter);
  app.set_version_flag("--version", "pd_query " + pd_build::Summary());
  std::string probe_path, scene_path;
  double probe_scale = 1.0, scene_scale = 1.0;
  std::vector<std::string> scene_pose;  // parsed like an input line
  bool coherent = false;
  app.add_option("PROBE_MESH", probe_path, "moving mesh (OBJ, STL, OFF, PLY)")->required();
  app.add_option("SCENE_MESH", scene_path, "static mesh (OBJ, STL, OFF, PLY)")->required();
  app.add_option("--probe-scale", probe_scale, "probe file units -> metres (default 1)");
  app.add_option("--scene-scale", scene_scale, "scene file units -> metres (default 1)");
  app.add_option("--scene-pose", scene_pose, "X_WS as x y z qw qx qy qz (default identity)")
      ->expected(7);
  app.add_flag("--coherent", coherent,
               "warm-start each line from the previous answer (a moving probe); "
               "default solves every line cold");
  pd::PolyDepthOptions options;
  app.add_option("--max-work", options.max_work,
                 "bounded time: stop after this many box + triangle tests (0: unbounded)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-time-us", options.max_time_us,
                 "bounded time: stop after this many microseconds (0: unbounded)")
      ->check(CLI::NonNegativeNumber);
  // The cold search's speed-for-accuracy knobs (PolyDepthOptions documents
  // each with its measured trade; bench_pd's knob sweep measures them per pair).
  app.add_option("--landings", options.num_maximally_clear,
                 "cold: support-plane starts out-projected onto the contact space, ranked by "
                 "where they land")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--iterated-starts", options.num_iterated_starts,
                 "cold: starts refined by iteration, closest landing first")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--iterated-starts-bounded", options.num_iterated_starts_bounded,
                 "cold, under --max-work or --max-time-us: at most this many starts iterated")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--start-gate", options.cold_start_gate,
                 "cold: a start after the first is iterated only if it lands within this "
                 "fraction above the best answer so far")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--shell-probes", options.cold_shell_probes,
                 "cold: directions probed at 0.995 of the best answer's length for the "
                 "other basins shallower than it (0: off)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--inner-probes", options.cold_inner_probes,
                 "cold: directions probed inside the best answer for shorter escapes "
                 "(0: off)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--deep-probes", options.cold_deep_probes,
                 "cold: free probes deeper inside the best answer that are refined "
                 "(pockets the other model encloses; 0: off)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--cold-join", options.cold_join,
                 "cold: a start stops where it comes this close (fraction of the models' "
                 "size) to an earlier start's path (default 0: off)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--creep-join-iterations", options.creep_join_iterations,
                 "coherent: from this iteration of a search on, its local model keeps the "
                 "earlier iterates' constraints still near (default 6; 0: off)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--screen-tol", options.cold_screen_tol,
                 "cold: starts stop once a step gains less than this (fraction of size), "
                 "then the best goes on (default 0: off)")
      ->check(CLI::NonNegativeNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }

  pd::Isometry3 X_WS = pd::Isometry3::Identity();
  if (!scene_pose.empty()) {
    std::string text;
    for (const std::string& field : scene_pose) text += field + " ";
    const pd::PoseLine parsed = pd::ParsePoseLine(text);
    if (parsed.kind != pd::PoseLine::Kind::kPose) {
      std::cerr << "pd_query: --scene-pose: "
                << (parsed.error.empty() ? "expected x y z qw qx qy qz" : parsed.error) << "\n";
      return kExitUsage;
    }
    X_WS = parsed.X_WP;
  }

  const auto probe = LoadModel(probe_path, probe_scale);
  if (!probe) return kExitMeshError;
  const auto scene = LoadModel(scene_path, scene_scale);
  if (!scene) return kExitMeshError;
  pd::PolyDepthSolver solver(probe, scene, options);

  bool any_failed = false;
  std::string line;
  for (long line_number = 1; std::getline(std::cin, line); ++line_number) {
    const pd::PoseLine parsed = pd::ParsePoseLine(line);
    if (parsed.kind == pd::PoseLine::Kind::kSkip) continue;
    nlohmann::ordered_json answer;
    if (parsed.kind == pd::PoseLine::Kind::kError) {
      answer = {{"error", "line " + std::to_string(line_number) + ": " + parsed.error}};
      any_failed = true;
    } else {
      try {
        answer = ToJson(solver.Solve(parsed.X_WP, X_WS, coherent));
      } catch (const std::exception& e) {
        answer = {{"error", "line " + std::to_string(line_number) + ": solver failed: " + e.what()}};
        any_failed = true;
      }
    }
    // Input echoed in errors may be invalid UTF-8: replace, do not throw.
    // Flushed per line so an interactive caller gets each answer at once.
    std::cout << answer.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace)
              << std::endl;
  }
  return any_failed ? kExitBadLine : kExitOk;
}
