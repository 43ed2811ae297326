#pragma once
// PolyDepthSolver::Impl: the state of one solver's searches (the warm-start
// state kept between queries, the current query's best answer, budget and
// scratch) and the phases of Solve that work on it, one file each:
//   polydepth.cc               Solve: the collision test at the query, the
//                              phases in order, verification, the result;
//   search_iteration.cc        a start's search: localise, in-project,
//                              out-project until |q| stops improving;
//   candidate_list_upkeep.cc   the leaf-pair list coherent queries walk;
//   coherent_restart.cc        steps 0, 1, 1b: the incremental update from
//                              the previous answer, restarts near it;
//   coherence_checks.cc        steps 2b-2e: cross-checks of a coherent answer
//                              and its neighbour basins;
//   cold_query.cc              step 2: support-plane starts, landed and the
//                              closest iterated; and the sampling-search
//                              fallback;
//   cold_probes.cc             step 2's shell, inner and deep probes, and
//                              step 2f: what a budget cut from a cold query,
//                              gone on with by the following coherent ones;
//   pocket_escape.cc           step 3a: out of thin free pockets.
// They share out_projection.h (the CCD move), contact_constraints.h
// (localisation), min_norm_point.h (in-projection), support_plane_starts.h
// and cold_starts.h (the cold starts' geometry).
// Internal to pd_core. Units: m; q_S is a translation of the probe in the
// scene frame S (ModelPair), from the query pose.
#include <array>
#include <chrono>
#include <functional>
#include <random>
#include <vector>

#include "pd_core/polydepth/cold_starts.h"
#include "pd_core/proximity/box_overlap.h"
#include "pd_core/proximity/inner_sphere_overlap.h"
#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/polydepth/min_norm_point.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/polydepth/support_plane_starts.h"
#include "pd_core/proximity/candidate_pairs.h"
#include "pd_core/proximity/descent_front.h"
#include "pd_core/proximity/leaf_pair_record.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/model_pair.h"

namespace pd {

struct PolyDepthSolver::Impl {
  // Under a budget the search stops at this share of it: the rest is kept for
  // the answer's finish (its verification, a pocket escape and the escaped
  // answer's localisation). haptic_work --max-time-us 900, 30 paths: 6
  // queries over 900 us, the worst 990 us (1049-1066 in earlier runs: a
  // search stopped at 900 us, then 100-250 us of finish); at 0.85 with the
  // escape's record (step 3a) none, the worst 891 us. Budget-stopped
  // queries 5 -> 12 of 84k, 0.95% deeper than unbounded on average; at 0.75
  // 27 stopped, one answer 108% deeper.
  static constexpr double kSearchShare = 0.85;
  // An iteration whose in-projection target lies within this many contact
  // distances of its start tests the target first (its localisation fused
  // with the surface test) and takes it when free, with no out-projection.
  // Traced on haptic_work's 30 paths, steps under 10 contact distances reached
  // a free target 85-100% of the time, under 100 about half, longer ones
  // rarely; each such out-projection cost ~500-2000 tests in a broad contact.
  // At 30: p99 work -1 to -4% per pair, max per path down up to 25%
  // (fandisk_elephant 18.1k -> 13.5k tests), medians the same, 6 of 84k
  // answers shallower (by up to 2.9%), none deeper; at 10 fandisk's max
  // fell to 16.8k only and at 20 not at all (its worst query's step is 20-30
  // distances); at 50 and 100 20-48 answers change, some deeper.
  static constexpr double kTargetFirstSteps = 30.0;
  // Neighbour-basin probes per query (coherence_checks.cc, step 2e): along
  // up to this many of the answer's contact normals, and one toward the
  // probe's motion.
  static constexpr int kBasinNormalProbes = 2;
  static constexpr int kBasinProbes = kBasinNormalProbes + 1;

  // A collision-free configuration and where it came from.
  struct Start {
    Vector3 q_S;
    Initializer origin;
    double contact_norm = 0.0;  // |q| after the first out-projection
    Vector3 contact_q_S = Vector3::Zero();
    int index = -1;  // in the query's list of starts (ColdProbes::start_dirs)
  };
  std::vector<ContactConstraint> constraints;
  MinNormScratch qp;
  std::vector<Start> starts;
  std::vector<double> landed_norms;  // cold: landing norms of the starts out-projected exactly
  std::vector<SupportPlaneStart> support_starts;
  std::vector<Vector3> inner_starts;  // cold: free probes below the best answer
  // What a cold query leaves to the following coherent queries when its
  // budget stops it (cold_probes.cc): its starts (landed again at the
  // query's pose, the closest ones it did not iterate iterated), then its
  // probes for shallower basins (the shell, then pockets), each a stage
  // that probes its sets of directions into inner_starts and then
  // iterates the free probes found. Any stage can stop and a later query
  // go on where it stopped.
  struct ColdProbes {
    bool pending = false;  // the next coherent queries go on
    int stage = 0;         // stage under way (0: the starts, 1: shell, 2: pockets)
    // The starts: the query's start directions (unit, S) and initializers,
    // those it iterated, and the landings of this stage (|q|, index), once
    // all landed sorted nearest first and iterated from next_iterated.
    std::vector<Vector3> start_dirs;
    std::vector<Initializer> start_origins;
    std::vector<int> iterated;
    std::vector<std::pair<double, int>> landed;
    size_t next_landing = 0;
    bool landings_sorted = false;
    size_t next_iterated = 0;
    // The probes.
    int set = 0;          // the stage's probe set under way (while probing)
    ProbeCursor cursor;   // where that set's probing stopped
    bool probed = false;  // the stage's probing is done: iterating its free probes
    size_t next = 0;      // next of inner_starts to iterate
    size_t earlier = 0;   // inner_starts[0, earlier) were found by an earlier query
    // Back to the first stage, keeping the vectors' storage.
    void Reset(int first_stage) {
      pending = false;
      stage = first_stage;
      landed.clear();
      next_landing = next_iterated = 0;
      landings_sorted = false;
      ResetProbes();
    }
    void ResetProbes() {
      set = 0;
      cursor = ProbeCursor{};
      probed = false;
      next = earlier = 0;
    }
  } cold_probes;
  // Lands the start q_S (free, m) on the contact space toward the query
  // (OutProject) unless it cannot land closer than `threshold` (m; 1e300:
  // no threshold), which a collision test settles for most such starts.
  // True with the landing in *q_c when it touched; *exact false when the
  // CCD stopped at a contact farther than the threshold.
  bool LandStart(const ModelPair& pair, double margin, const Vector3& q_S, double threshold,
                 Vector3* q_c, bool* exact);
  // Runs the stages from where cold_probes says until all are done (true,
  // pending cleared) or the budget stops them (false).
  bool RunColdProbes(const ModelPair& pair, const PolyDepthOptions& opt,
                     PenetrationResult* result);
  // Stage 0 of RunColdProbes: the starts, landed again and the closest
  // the cold query did not iterate iterated.
  bool RestOfColdStarts(const ModelPair& pair, const PolyDepthOptions& opt,
                        PenetrationResult* result);
  std::mt19937_64 rng;
  CandidatePairs candidates;           // leaf pairs near the last contact (warm start)
  LeafPairRecord record;               // leaf pairs near the last recorded out-projection
  DescentFront front;                  // where the last full descent ended
  IntersectionHint intersection_hint;  // where the last probe's surfaces crossed
  ProbeBoxCache probe_boxes;
  PlacedInnerSpheres inner_spheres;  // the pair's inner spheres at this query's rotation  // the probe node boxes at this query's rotation
  bool list_follows_iterates = false;  // this query may still move the list to an iterate
  // PolyDepthOptions::defer_list_builds: the list being built in
  // PrepareNext (it replaces `candidates` once complete), and the build the
  // current query asks for: around its answer shifted by wanted_lead, of
  // radius wanted_radius (the first ask of a query stands: where the list
  // did not cover the query, else where an iterate left it).
  CandidatePairs next_candidates;
  bool build_wanted = false;
  Vector3 wanted_lead = Vector3::Zero();
  double wanted_radius = 0.0;
  void WantBuild(const Vector3& lead, double radius) {
    if (build_wanted) return;
    build_wanted = true;
    wanted_lead = lead;
    wanted_radius = radius;
  }
  // Goes on with the deferred build; once complete it replaces the list in
  // use. Returns whether it completed.
  bool AdvanceDeferredBuild(const std::function<bool()>& pause, ProximityCounters* counters) {
    if (!next_candidates.ContinueBuild(pause, counters)) return false;
    std::swap(candidates, next_candidates);
    next_candidates.Invalidate();
    return true;
  }
  int list_builds = 0;  // this query's list builds and their wall time (us)
  double list_build_us = 0.0;
  // The list a query plans around where it will work (PlanList), built once
  // the query is known to collide (BuildPlannedList).
  struct ListPlan {
    bool build_pending = false;
    Vector3 build_center = Vector3::Zero(), build_lead = Vector3::Zero();
    double build_radius = 0.0;
    Vector3 need_center = Vector3::Zero();  // where the query's list must reach, and how far
    double need = 0.0;
  };
  ListPlan PlanList(const ModelPair& pair, const PolyDepthOptions& opt, bool have_prediction,
                    const Vector3& q_pred, double motion);
  void BuildPlannedList(const ModelPair& pair, const PolyDepthOptions& opt, const ListPlan& plan);
  // A valid answer's deferred build (PolyDepthOptions::defer_list_builds),
  // around it, for PrepareNext.
  void BeginDeferredBuildAroundAnswer(const ModelPair& pair, const PolyDepthOptions& opt);
  // About how many leaf pairs the list holds (0 when there is none).
  double ListLeafPairs() const;
  // Where the last list was dense, the next pairs small subtrees
  // (CandidatePairs::Grain): a dense patch's build is the query's work.
  CandidatePairs::Grain NextGrain() const;
  // The deferred build under way, completed in this query and put in use
  // (candidate_list_upkeep.cc).
  void FinishDeferredBuild(const ModelPair& pair);
  void BuildList(const ModelPair& pair, const Vector3& q_center_S, double radius);
  // Triangle pairs that intersected lately: at the query poses (the next
  // query's own collision test and the cross-check's probes start from it),
  // and at the iterates. Kept apart: an iterate's pair, near the answer,
  // rarely intersects at the next query pose, millimetres deeper (cow_armadillo
  // median 50 -> 48.5 us, work 833 -> 814 tests).
  CollisionWitness query_witness;
  CollisionWitness witness;
  // Step 2e's probe directions for this query, and the pairs its collision
  // tests hit by direction (kept for the next query's) and lately.
  std::array<Vector3, kBasinProbes> basin_directions;
  struct DirectionWitness {
    Vector3 u_S = Vector3::Zero();
    CollisionWitness witness;
  };
  std::array<DirectionWitness, kBasinProbes> basin_witnesses, next_basin_witnesses;
  int num_basin_witnesses = 0, num_next_basin_witnesses = 0;
  CollisionWitness basin_witness;
  // The coherent answer a basin probe replaced in the previous query (when
  // it did): step 1's last coherent start. Written by step 2e, which runs
  // after step 1 reads it.
  Vector3 previous_replaced_q_S = Vector3::Zero();
  bool has_previous_replaced = false;
  // Into basin_directions: the distinct normals of `constraints` (the
  // answer's, unit answer direction n) in the probe window, then the
  // direction leaning toward the probe's motion v_S across n; returns how
  // many.
  int BasinProbeDirections(const Vector3& n, const Vector3& v_S);
  // Whether the probe collides at q0 (along u), witnesses first (see
  // kBasinWitnessCos); a hit is kept for the next query's probe along u.
  bool BasinProbeCollides(const ModelPair& pair, const Vector3& q0, const Vector3& u);
  void EndBasinProbes();
  ProximityCounters counters;
  std::vector<ContactConstraint> previous_constraints;  // at the previous answer
  std::vector<ContactConstraint> unit_constraints;      // scratch of ClearingDirection
  // An iteration's local model (`constraints`, joined by the earlier
  // iterates' when creeping) and the one before it (without the margin).
  std::vector<ContactConstraint> joined, earlier;
  // Into `joined`: the constraints localised at q_c and, with `creeping`,
  // those of the earlier iterates' models within `distance` of q_c by plane
  // distance (a feature pair the localisation found is not repeated). A
  // coherent search this long creeps across a basin switch, a few
  // micrometres per step: each in-projection satisfies the features found
  // where it starts, and its sweep runs into ones just left behind (fandisk
  // on elephant: 13 iterations of 3-35 um gains). With those kept, the
  // switch ends in fewer iterations per query or goes on in the next
  // (haptic_work, five paths: max work knot1_bunny 43.8k -> 25.1k,
  // fandisk_elephant 24.2k -> 17.5k, cow_armadillo 17.1k -> 16.3k; the
  // answers' depths as often 5% shallower as deeper; from the 4th iteration
  // the same max, more answers deeper, total work +0.6%).
  void JoinEarlierConstraints(const Vector3& q_c, double distance, bool creeping);
  double anchor_depth = 0.0;                  // |q| the coherent answers are measured against (m)
  Vector3 anchor_n_S = Vector3::Zero();       // direction of the answer that set it
  double anchor_probe_depth = 0.0;            // |q| at the last probe along anchor_n_S (m)
  int check_next = -1;                        // next direction of the running cross-check; -1: none
  Vector3 check_start_q_S = Vector3::Zero();  // the answer when that check started (m)
  void SetAnchor(const Vector3& q_S) {
    anchor_depth = q_S.norm();
    anchor_n_S = q_S / std::max(anchor_depth, 1e-300);
    anchor_probe_depth = 0.0;
  }
  // Work budget (PolyDepthOptions::max_work / max_time_us) of this query.
  int64_t work_limit = 0;
  double time_limit_us = 0.0;
  std::chrono::steady_clock::time_point t_start;
  bool stopped_early = false;
  // A cold query's landings stopped at their share of the budget: not
  // converged, but the search goes on (stopped_early would end it).
  bool landings_cut = false;
  // A warm query's look-ahead. Its steps between two OutOfBudget checks (a
  // localisation, a list build) cannot stop midway, and its budget is the
  // servo's: a check stops the search where a step as long as the query's
  // longest so far would end past the search's share. (Without it, on a
  // loaded VM, a check at 760 us of a 900 us budget let a 110 us
  // localisation run and the answer's finish follow: cow_armadillo 1.26 ms.
  // Work-bounded at 12k tests on haptic_work's paths: max 13.5k -> 12.0k
  // tests, depths within 1e-5.) Not in a cold query: its steps are a large
  // part of its budget and the reserve absorbs them (cold queries ended by
  // 0.98 ms of 1 ms); stopping before them raised the mean excess over the
  // unbounded answer at 16k tests from 4.3% to 5.6% (8 pairs x 32 cases).
  bool look_ahead = false;
  double last_check_us = -1.0;  // this query's last check (us; -1: none yet)
  int64_t last_check_work = -1;
  double longest_step_us = 0.0;  // the longest stretch between two checks
  int64_t longest_step_work = 0;
  // True once the search's share of the budget (kSearchShare) is spent (with
  // the look-ahead: or would be by the end of a step as long as the longest)
  // and some verified answer exists.
  bool OutOfBudget() {
    if (best_origin == Initializer::kNone) return false;
    if (stopped_early) return true;
    if (!Bounded()) return false;
    const double now_us = time_limit_us > 0.0 ? ElapsedUs() : 0.0;
    const int64_t work = counters.total();
    if (look_ahead && last_check_work >= 0) {
      longest_step_us = std::max(longest_step_us, now_us - last_check_us);
      longest_step_work = std::max(longest_step_work, work - last_check_work);
    }
    last_check_us = now_us;
    last_check_work = work;
    return stopped_early = Spent(kSearchShare, now_us + longest_step_us, work + longest_step_work);
  }
  const std::function<bool()> stop_ccd = [this] { return OutOfBudget(); };
  // The query has a work or time budget (PolyDepthOptions::max_work,
  // max_time_us).
  bool Bounded() const { return work_limit > 0 || time_limit_us > 0.0; }
  // Wall time since this query began (us).
  double ElapsedUs() const {
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t_start)
        .count();
  }
  // True once `share` of the budget is spent (never without a budget).
  bool BudgetSpent(double share = 1.0) const {
    return Spent(share, time_limit_us > 0.0 ? ElapsedUs() : 0.0, counters.total());
  }
  // True if `share` of the budget is spent at `elapsed_us` and `work` tests.
  bool Spent(double share, double elapsed_us, int64_t work) const {
    return (work_limit > 0 && work >= share * work_limit) ||
           (time_limit_us > 0.0 && elapsed_us >= share * time_limit_us);
  }
  // Warm-start state, relative to the scene (so a moving scene is fine).
  bool has_previous = false;       // previous frame collided and was solved
  bool has_previous_free = false;  // previous frame was collision-free
  Vector3 previous_q_S = Vector3::Zero();
  Vector3 previous_n_S = Vector3::Zero();
  RelativePose previous_X_SP;

  // The configuration of this query last verified free by a full collision
  // test (so the final check need not repeat it), and the one an iterate's
  // localisation last found with no surfaces crossing (the final check of
  // it needs only the containment test).
  Vector3 verified_q_S = Vector3::Constant(1e300);
  Vector3 surfaces_free_q_S = Vector3::Constant(1e300);
  // Where `constraints` were last localised (they are reused for regions).
  Vector3 constraints_q_S = Vector3::Constant(1e300);
  // The localisation Iterate made at the best answer when it was the best
  // (kept as collected, before the margin): the pocket check and the
  // result's contacts need it after later starts localised elsewhere.
  std::vector<ContactConstraint> best_constraints;
  Vector3 best_constraints_q_S = Vector3::Constant(1e300);
  // Best verified-free contact configuration of the current query.
  Vector3 best_q_S = Vector3::Zero();
  double best_norm = 0.0;
  Initializer best_origin = Initializer::kNone;
  int iterations = 0;
  int iterated_starts = 0;  // Iterate calls this query (PenetrationResult::iterated_starts)

  // A coherent iterate that has left the list's reach moves the list to it,
  // once per query (candidate_list_upkeep.cc).
  void FollowWithList(const ModelPair& pair, const PolyDepthOptions& opt, double size,
                      const Vector3& q_S);

  // Cold: the configurations the starts iterated so far went through, each
  // with |q| where its start ended (+inf while the start runs). An iterate
  // within join_distance (m) of one whose start ended no deeper than the
  // iterate joins that start's descent (PolyDepthOptions::cold_join; 0: off).
  struct TrailPoint {
    Vector3 q_S;
    double end_norm;
  };
  std::vector<TrailPoint> trail;
  size_t trail_start = 0;  // the running start's first point in `trail`
  double join_distance = 0.0;
  bool JoinsAnEarlierStart(const Vector3& q_c, double norm_c) const {
    if (join_distance <= 0.0) return false;
    for (const TrailPoint& t : trail)
      if (t.end_norm <= norm_c && (q_c - t.q_S).squaredNorm() < join_distance * join_distance)
        return true;
    return false;
  }
  // The running start ended at end_S: its points join the trail.
  void EndStart(const Vector3& end_S) {
    if (join_distance <= 0.0) return;
    trail.push_back({end_S, 0.0});
    for (size_t i = trail_start; i < trail.size(); ++i) trail[i].end_norm = end_S.norm();
    trail_start = trail.size();
  }
  // Iterates localisation, in-projection and out-projection from a contact
  // configuration q_c (free, touching) until |q| stops improving.
  // A cold start passes `abandon` to stop once it cannot beat the best.
  // Returns where it ended (its last contact configuration).
  Vector3 Iterate(const ModelPair& pair, const PolyDepthOptions& opt, double size, Vector3 q_c,
                  Initializer origin, StartAbandon* abandon = nullptr);

  // The unit direction that moves the probe off every one of `cs` at once
  // (the shortest x with n_i·x >= 1 for all, normalised), and in *clearance
  // the least rate min_i n_i·d at which it does; zero vector and clearance
  // <= 0 when no direction clears them all (the probe is wedged).
  std::vector<ContactConstraint> pocket_constraints;  // the pocket check's (EscapePocket)
  Vector3 ClearingDirection(const std::vector<ContactConstraint>& cs, double tol,
                            double* clearance);

  // Localises at q_S and tests it free in the same pass (the surfaces, then
  // the models' containment). Free: true, `constraints` q_S's and q_S
  // verified. Not: false, `constraints` no configuration's (the pass stopped
  // at the first intersecting triangle pair, recorded in *witness if given).
  bool LocaliseIfFree(const ModelPair& pair, const Vector3& q_S, double distance,
                      CollisionWitness* witness);
  // Localises at the best answer unless `constraints` hold it already; the
  // same localisation kept from Iterate when there is one (same pair, same
  // configuration: the same constraints).
  void LocaliseAtBest(const ModelPair& pair, double contact_distance);
  // The best answer exists and is verified free (by a test this query
  // made, else now).
  bool BestVerified(const ModelPair& pair);

  void Offer(const Vector3& q_S, Initializer origin) {
    const double n = q_S.norm();
    if (n < best_norm) {
      best_norm = n;
      best_q_S = q_S;
      best_origin = origin;
    }
  }

  // The phases of Solve, in its order.
  // Step one of the incremental update (coherent_restart.cc): the previous
  // answer's local model at the new pose; true and its in-projection in
  // *q_pred if the motion is small enough for it.
  bool PredictFromPrevious(const ModelPair& pair, const PolyDepthOptions& opt, double motion,
                           Vector3* q_pred);
  void CoherentUpdate(const ModelPair& pair, const PolyDepthOptions& opt, const Vector3& q_pred);
  void RestartNearPreviousAnswer(const ModelPair& pair, const PolyDepthOptions& opt, double motion,
                                 double turn);
  void RestartFromFreeFrame(const ModelPair& pair, const PolyDepthOptions& opt);
  void ColdQuery(const ModelPair& pair, const PolyDepthOptions& opt, PenetrationResult* result);
  void CheckCoherentAnswer(const ModelPair& pair, const PolyDepthOptions& opt,
                           PenetrationResult* result);
  // Goes on with the probes of a budget-stopped cold query (cold_probes.cc).
  void ResumeColdProbes(const ModelPair& pair, const PolyDepthOptions& opt,
                        PenetrationResult* result);
  void EscapePocket(const ModelPair& pair, const PolyDepthOptions& opt, PenetrationResult* result);
  // The fallback when no start gave a verified answer: out-projections
  // from num_sampling_directions support-plane configurations, the closest
  // landing iterated.
  void SamplingSearch(const ModelPair& pair, const PolyDepthOptions& opt);
};

}  // namespace pd
