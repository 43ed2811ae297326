#pragma once
// What a penetration-depth query returns. All vectors are in world W, lengths
// in metres. The probe P is the moving mesh; the scene object S is the other.
#include <array>
#include <cstdint>

#include "pd_core/geometry/pose.h"

namespace pd {

// Which initialiser produced the collision-free start that won.
enum class Initializer : uint8_t {
  kNone = 0,           // no collision, nothing to solve
  kMotionCoherence,    // previous answer of this pair
  kMaximallyClear,     // precomputed support-plane separations of the models
  kCentroidDifference, // straight out along centroid_P - centroid_S
  kRandom,             // random directions
  kSamplingSearch,     // dense directional sampling (last resort)
};
const char* InitializerName(Initializer init);

// A contact region: features of P and S that touch when P is moved by the PD
// translation, grouped by normal. Its local PD is (d·n) n, d the PD vector.
struct ContactRegion {
  Vector3 p_W = Vector3::Zero();   // contact point on P at the query pose (m)
  Vector3 n_W = Vector3::UnitZ();  // unit normal, pointing from S into P's escape side
  double local_depth = 0.0;        // d·n (m), >= 0
  int num_features = 0;            // feature pairs merged into this region
  Vector3 local_pd_W() const { return local_depth * n_W; }
};

inline constexpr int kMaxContactRegions = 16;

struct PenetrationResult {
  bool in_collision = false;  // P at the query pose intersects or is contained in S
  bool valid = true;          // translation verified to leave P collision-free
  double depth = 0.0;         // |translation| (m); an upper bound on the true PD
  Vector3 translation_W = Vector3::Zero();  // move P by this to separate (m)
  Vector3 normal_W = Vector3::Zero();       // translation / depth (unit), zero if free
  std::array<ContactRegion, kMaxContactRegions> regions{};
  int num_regions = 0;
  int num_contacts = 0;  // feature pairs (vertex-face, face-vertex, edge-edge) at the answer
  int iterations = 0;    // contact-space projection iterations
  int starts = 0;        // cold starts out-projected (0 when warm starts sufficed)
  // Starts iterated: the contact-space searches this query ran, each from
  // one free contact configuration (a cold start's landing, a shell or inner
  // probe's, a coherent start); `iterations` is their steps in total.
  int iterated_starts = 0;
  Initializer initializer = Initializer::kNone;
  // False when a work budget (PolyDepthOptions::max_work) stopped the search
  // early: the answer is still verified free (an upper bound), just not
  // known to be a local optimum.
  bool converged = true;
  // Warm-started (coherent) queries: no coherent start gave an answer and
  // the query restarted cold.
  bool warm_start_failed = false;
  // A coherent answer had grown much deeper than its anchor and this query
  // ran part of the check for a shorter one (free directions around the
  // query inside the answer's length, a few per query; the shorter answer on
  // the same side wins), or probed once back along the direction of the
  // shallowest answer since the last check, which it had turned from.
  bool cross_checked = false;
  // Probes run along the answer's own contact normals 10-37 degrees from it
  // (a coherent query with no check or turn probe), and whether one of them
  // led to a shorter answer in another basin, which this query returns.
  int basin_probes = 0;
  bool basin_switched = false;
  // A coherent query that went on with the probes for shallower basins of
  // a cold query its budget had stopped (PolyDepthOptions::max_time_us,
  // max_work): the rest of that cold search, where it stopped.
  bool cold_probes_resumed = false;
  // Times the answer was found inside a pocket of free space thinner than
  // PolyDepthOptions::pocket_thickness (it is moved out of the pocket when a
  // free configuration with room beyond is found within 16x the contact
  // distance; otherwise it stays, free at itself).
  int pocket_escapes = 0;
  int64_t box_tests = 0;       // bounding-box tests this query made (cost counter)
  int64_t triangle_tests = 0;  // triangle-pair tests this query made
  // Where that work (box + triangle tests) went, by kind of pair query; the
  // five sum to box_tests + triangle_tests.
  struct Work {
    int64_t collision = 0;       // collision tests (the query's own, starts, probes, checks)
    int64_t localisation = 0;    // contact localisations (feature pairs near a configuration)
    int64_t out_projection = 0;  // translational CCD onto the contact space
    int64_t list_builds = 0;     // leaf-pair lists near the contact (warm queries)
    int64_t other = 0;  // the rest (cold starts' support planes, warm answers' PD lower bound)
  } work;
  // Warm queries: times this query rebuilt the list of leaf pairs near the
  // contact (the probe slid out of the last one's reach, or an iterate moved
  // millimetres away from it; at most 2) and their wall time (microseconds,
  // part of time_us). A rebuild descends both hierarchies around the
  // contact: on a sliding contact it is the usual cause of a slow query.
  int list_builds = 0;
  double list_build_us = 0.0;
  double time_us = 0.0;  // solver wall time (microseconds)
};

}  // namespace pd
