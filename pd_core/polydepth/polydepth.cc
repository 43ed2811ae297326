#include "pd_core/polydepth/polydepth.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "pd_core/proximity/candidate_pairs.h"
#include "pd_core/proximity/descent_front.h"
#include "pd_core/proximity/leaf_pair_record.h"
#include "pd_core/polydepth/cold_starts.h"
#include "pd_core/polydepth/contact_constraints.h"
#include "pd_core/polydepth/contact_regions.h"
#include "pd_core/polydepth/depth_lower_bound.h"
#include "pd_core/geometry/fibonacci_sphere.h"
#include "pd_core/proximity/mesh_collision.h"
#include "pd_core/proximity/solid_containment.h"
#include "pd_core/polydepth/min_norm_point.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/polydepth/support_plane_starts.h"
#include "pd_core/proximity/translational_ccd.h"

namespace pd {

const char* InitializerName(Initializer init) {
  switch (init) {
    case Initializer::kNone: return "none";
    case Initializer::kMotionCoherence: return "motion_coherence";
    case Initializer::kMaximallyClear: return "maximally_clear";
    case Initializer::kCentroidDifference: return "centroid_difference";
    case Initializer::kRandom: return "random";
    case Initializer::kSamplingSearch: return "sampling_search";
  }
  return "unknown";
}

namespace {

// Cross-check a coherent answer once it is this many times deeper than its
// anchor plus this fraction of the pair's size (the check is spread over
// queries, so it can start early: 1.2 against 1.5 found shorter answers
// sooner on the benchmark's haptic paths). A tool pushed 3 mm deep grows its
// answer 0.1 mm per millisecond along one basin while another, 20-50 degrees
// away, stays shallower: at 1.2 + 5e-3 x size the check waited for 1 mm of
// growth (cow_armadillo followed a basin 2.5 -> 3.6 mm for 20 ms over one at
// 2.8 mm). At 1.1 + 1e-3 with the probes at 0.98 (below), mean error against
// a cold solve at every 20th colliding pose of the 30 haptic paths 0.71 ->
// 0.49% (cow_armadillo 1.44 -> 1.02%, fandisk_elephant 1.41 -> 0.85%), work
// median cow_armadillo +16%, fandisk_elephant +7%, the others unchanged.
constexpr double kReanchorGrowth = 1.1;
constexpr double kReanchorFloor = 1e-3;
// A query's iterations reach this many contact distances beyond the
// configuration a list is built or checked around (its localisations and
// their out-projections): a list must cover that much more.
constexpr double kListIterationRoom = 6.0;
// A list built while sliding is centred this fraction of its radius ahead.
constexpr double kListLead = 0.6;
// A list reaches as far as this many queries of the current motion (a fast
// slide rebuilt it every other query: those rebuilds set the median), at
// least candidate_radius and at most this many times it (a rebuild's cost
// grows with the square of the reach on a flat patch).
constexpr double kListTicks = 3.0;
constexpr double kListMaxReach = 2.0;
// No list is built for a query that would need it wider than this many
// times its usual radius.
constexpr double kListMaxNeed = 2.0;
// A list is sized for about this many entries where the contact is dense
// (see the list block in Solve): it bounds a rebuild's work and the list's
// memory (48 B per entry). Below it a rebuild's cost is set by the leaves,
// not the reach: leaf boxes are several times the radius (bull_bunny: ~7 box
// tests per entry, 89% of them on boxes of half-diagonal under 16 radii), so
// a coarse front or front tracking would save little. Measured since: a
// rebuild that updates the last build's cut of the pair hierarchy (Ehmann
// and Lin's front tracking, with merging) tests half as many pairs, but its
// time fell ~15% on average and not at all on the large lists that set p99:
// consecutive lists are ~1.6 radii apart, so most of the front near the
// contact is tested again, and every entry must be. Carrying entries to the
// next list untested (gaps moved along their axes) kept the ones a slide
// passes along, not away from: lists grew and medians doubled. Tried and dropped:
// building the next list ahead in slices over the queries the current one
// still covers (the lists built ahead sat worse, so more rebuilds, and the
// slices landed on queries with work of their own: p99 and max work up on
// knot1_camel and fandisk_elephant; measured again with a resumable descent
// and the slice spread over the queries left: fresh builds fell ~85% but
// total work rose 30-45% and every p99 and max rose). Nor does a list swept
// along the motion (a capsule of configurations instead of a ball) last
// longer for free: on a dense patch its entries grow with its length
// (fandisk_elephant at 0.36 mm: 3.3k for the ball, 9.8k with a 1.2 mm
// sweep), so the build work per millimetre slid stays the same; builds fell
// 25-45%, p99 work did not, and fandisk's max doubled.
constexpr double kListMaxEntries = 2000.0;
// A list is built of twig pairs (CandidatePairs::Grain) where the list it
// replaces held more than this many leaf pairs; the reach cap above counts a
// twig-pair entry as this many leaf pairs. An entry holds 2.28 on average
// (measured on the benchmark's haptic paths against leaf-pair lists of the
// same centre and reach; 1.61 with one-level scene twigs), but counting it
// so capped the lists that cow_armadillo's median queries walk: median work
// 461 -> 468 (1.9) and 470 (2.3), fandisk_elephant's p99 8422 -> 8188.
// With one-level twigs on both sides, on fandisk_elephant's
// dense patch (haptic_work): p99 work 12787 -> 9930 tests, max 29261 ->
// 27048, median 250 -> 263; the other pairs' answers unchanged, their work
// within 2% (knot1_bunny p99 -7%, max +4%).
// Twig pairs everywhere made every median 15-60% dearer (a walk descends
// each entry it cannot skip: a few box tests where a leaf pair costs one).
constexpr double kTwigListLeafPairs = 1000.0;
constexpr double kTwigEntryLeafPairs = 1.5;
// A cross-check of a coherent answer probes this many directions around the
// query, this many per query (spread over queries so no query pays for the
// whole check), each at this fraction of the coherent answer's length; a
// direction that lands shorter is iterated this many times (the following
// queries' coherent updates go on from it).
constexpr int kCheckDirections = 64;
constexpr int kCheckStride = 27;  // coprime with kCheckDirections: spread order
constexpr int kCheckPerQuery = 4;
// While a check runs and the answer grew more than kCheckFastGrowth since
// the previous query (pushed into its basin: 3-7% per query in
// cow_armadillo's crevices), another basin overtakes it within a few
// queries: the check probes kCheckPerQueryFast directions per query then.
// haptic_work's 30 paths against a cold solve at every 20th colliding pose
// (4204 poses): mean error 0.42 -> 0.38% (cow_armadillo 0.87 -> 0.68%),
// cow_armadillo p99 work +2%, fandisk_elephant +8%, max +4%; bench_pd's
// cow_armadillo path 0 against the reference (64 poses) 1.63 -> 1.04%
// (its 19% pose is test_crevice_basin_trade.cc's). 16 probes: the same
// errors on the 4204 poses, p99 work +3 and +17%; also starting a check on
// fast growth: 0.41%, median work +10%.
constexpr double kCheckFastGrowth = 0.03;
constexpr int kCheckPerQueryFast = 12;
constexpr double kCheckRadius = 0.98;
// (4, not 2, since the checks start sooner: a probe's basin iterated twice
// was often reported mid-way, 24% above the shortest escape within 30
// degrees of it on the torus-knot test path; at 4 the same errors and work.)
constexpr int kCheckIterations = 4;
// A coherent answer this many times deeper than the anchor and turned from
// its direction by more than acos(kAnchorProbeCos) gets one probe along it,
// and another each time it has grown this many times deeper since.
constexpr double kAnchorProbeGrowth = 1.05;
constexpr double kAnchorProbeCos = 0.985;  // 10 degrees
// A check or turn probe is skipped while the answer is proved within this
// fraction of the PD (depth_lower_bound.h): a vertex of its contact keeps
// that far from the other surface. At 1/kCheckRadius - 1 the proof says
// exactly that every probe (at kCheckRadius of the answer's length) would
// collide: the check cannot find anything, so it ends. On the bench's haptic
// paths the probes cost ~130 tests each and almost all collided (2718 of
// 2739 on cow_armadillo); the proof costs ~60: median work cow_armadillo
// 639 -> 454 (500 at a 1% slack), fandisk_elephant 273 -> 250; mean error
// on 160 reference poses per path 5.01 -> 5.07% summed over the five pairs
// (cow 3.02 -> 3.16%, fandisk 1.07 -> 1.23%, knot1_bunny 0.48 -> 0.23%:
// which basin a path follows moves either way).
// (Kept at 5% with the probes at 0.98, not 2%: the same errors, and the
// tighter proof settles fewer checks, cow_armadillo's median work +12%.)
constexpr double kProvedSlack = 1.0 / 0.95 - 1.0;
// A cold query ranks the best num_maximally_clear of at least this many
// support-plane directions.
constexpr int kMinSupportDirections = 48;
// PolyDepthOptions::cold_shell_probes: probed at this fraction of the best
// answer's length (0.995 against 0.98 and 0.99, with one iterated start:
// 0.57 against 0.71 and 0.65% mean |error| on bench_pd's random scenario,
// the same time; 0.998 the same as 0.995), and the first this many free
// ones iterated (2, 4 or 8: the same answers; a free shell probe is rare,
// 0.1 per query).
constexpr double kShellRadius = 0.995;
constexpr int kShellIterated = 4;
// Directions of PolyDepthOptions::cold_deep_probes (96 against 48 or 192:
// the same torus-knot error as 192 at three quarters of its work).
constexpr int kDeepProbeDirections = 96;
// A pocket check moves the answer off the feature pairs within this many
// pocket thicknesses of touching: those that bound the pocket. With all the
// answer's feature pairs (up to contact_tol away) the probe was often
// wedged: no one direction clears pairs that face each other across a
// contact, though the pocket itself opens (cow_armadillo: 3 answers on 30
// paths left in pockets).
constexpr double kPocketBoundSlack = 4.0;
// Directions this close to the coherent answer's are its own basin.
constexpr double kCheckOwnBasinCos = 0.9;
// An answer more than 120 degrees from the coherent one points back through
// the object: a thin wall pushed from one side keeps pushing back.
constexpr double kFlipCos = -0.5;

// 2e. Between checks, each coherent answer is probed along up to
// kBasinNormalProbes of its own contact normals that lie kBasinNearCos to
// kBasinFarCos from it (10-37 degrees), at kCheckRadius of its length. The
// tool often touches one surface with part of its contact while another
// part could slide off an edge: a shallower basin then opens 10-40 degrees
// from the followed answer, along the normal of the features it would leave
// by, and a check, started only by growth, sees it late or never (it skips
// directions within 26 degrees of the answer). On cow_armadillo's 6 haptic
// paths, with a cold solve at every colliding pose (15.5k poses): a fifth of
// the poses followed another basin than the cold solve, more than 10
// degrees off (most 10-40), carrying 0.87 of the 0.93% mean error. A probe's landing is free 2.5% of
// the time and then almost always shorter (80 of 82). Mean error 0.93 ->
// 0.75% (1 probe: 0.80%, 3: 0.73%), median work +3-14%, p99 -2%, the same
// max; the other haptic pairs, against a cold solve at every 20th colliding
// pose of their 6 paths: 0.15-0.63 -> 0.10-0.30% (fandisk_elephant median
// work +5%, the others +1-2%). Normals 5-10 degrees off were free 0.4% of
// the time, 45-72 degrees never.
// One more probe leans kBasinMotionAngle from the answer toward the
// probe's motion since the last query (its part across the answer): of the
// poses still in another basin with these probes (cow_armadillo path 0, more
// than 2% deep), the shallower basin lay within 60 degrees of that motion
// about the answer on 253 of 309 and past 90 degrees on 8 (a slide opens
// new contact ahead of the tool). With it the 6 paths' mean error 0.75 ->
// 0.60%, median work +1-8% (angles 14-27 degrees: the same; a second
// probe at 35 degrees: 0.57% at +4-7% more; the motion probe alone: 0.67%,
// but the other pairs lose half their gain); the other pairs 0.10-0.30 ->
// 0.10-0.27%.
constexpr int kBasinNormalProbes = 2;
constexpr int kBasinProbes = kBasinNormalProbes + 1;
constexpr double kBasinNearCos = 0.985;  // 10 degrees
constexpr double kBasinFarCos = 0.8;     // 37 degrees
constexpr double kBasinMotionAngle = 20.0 * M_PI / 180.0;
// Contact normals this close are one probe direction (3 degrees).
constexpr double kSameNormalCos = 0.9986;
// Almost every basin probe collides, just short of the boundary: the pair
// that intersected at the last query's probe in about the same direction
// (within kBasinWitnessCos, 18 degrees) or at the latest probe, then the
// triangle pairs of the kBasinViolatedWitnesses answer constraints the probe
// violates most, settle most of them in a few triangle tests before a full
// collision test (cow_armadillo path 0, 1500 colliding probes: 91k -> 46k
// tests; 1126 -> 1340 of them under 40 tests).
constexpr double kBasinWitnessCos = 0.95;
constexpr int kBasinViolatedWitnesses = 2;

// A collision-free configuration and where it came from.
struct Start {
  Vector3 q_S;
  Initializer origin;
  double contact_norm = 0.0;  // |q| after the first out-projection
  Vector3 contact_q_S = Vector3::Zero();
};

}  // namespace

namespace {

// Under a budget, a cold query's landings stop once this share of the
// search's part of it (kSearchShare) is spent (with one landed): the rest
// iterates the closest landing. On 24
// random cases of 13 real pairs at max_time_us 1000: mean error 19, 17
// and 16% at 0.25, 0.5 and 0.8 (at 3000: 8.1, 8.5, 8.4%).
constexpr double kColdLandingShare = 0.5;
// Under a budget the search stops at this share of it: the rest is kept for
// the answer's finish (its verification, a pocket escape and the escaped
// answer's localisation). haptic_work --max-time-us 900, 30 paths: 6
// queries over 900 us, the worst 990 us (1049-1066 in earlier runs: a
// search stopped at 900 us, then 100-250 us of finish); at 0.85 with the
// escape's record (step 3a) none, the worst 891 us. Budget-stopped
// queries 5 -> 12 of 84k, 0.95% deeper than unbounded on average; at 0.75
// 27 stopped, one answer 108% deeper.
constexpr double kSearchShare = 0.85;
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
constexpr double kTargetFirstSteps = 30.0;
// A coherent restart's step-offs of 1 and 4 motions (along the previous
// answer and with the motion undone) come first in its list of candidates;
// the clearing direction is tried before the rest (Solve, step 1).
constexpr int kNearStepOffs = 4;
// Room in pocket thicknesses, in the record made for a pocket escape (step
// 3a), for the escape's move (2-8 thicknesses on haptic_work's paths).
constexpr double kEscapeRecordRoom = 16.0;

// Out-projection: from a free q_from toward q_to, the last free point before
// first contact, backed off by `margin` (m) along the motion. Returns q_to if
// the whole segment is free. *touched tells which. With `s_stop` (see
// FirstContactAlongTranslation) a contact found before it ends the search:
// *exact (if given) is false then, and the point returned lies before the
// exact one. With `record` (not with s_stop), the CCD records the leaf pairs
// near the sweep and the record answers for the point returned if touching
// (the localisation there follows; see leaf_pair_record.h).
Vector3 OutProject(const ModelPair& pair, const Vector3& q_from, const Vector3& q_to,
                   double margin, bool* touched, double s_stop = -1.0,
                   bool* exact = nullptr, LeafPairRecord* record = nullptr) {
  const Vector3 d = q_to - q_from;
  const double len = d.norm();
  if (exact) *exact = true;
  if (record) record->Invalidate();
  if (len <= 0.0) {
    *touched = false;
    return q_to;
  }
  bool recorded = false, stopped = false;
  const double s = FirstContactAlongTranslation(pair, q_from, d, s_stop, record, &recorded, &stopped);
  if (s < 0) {
    *touched = false;
    if (record && recorded) {  // a free sweep's record holds the pairs near its end too
      record->q_S = q_to;
      record->valid = true;
    }
    return q_to;
  }
  // Stopped by the caller's budget (pair.stop_ccd): s is where the sweep is
  // known free, short of the contact; the point returned is free.
  *touched = true;
  if (exact) *exact = !stopped && s >= s_stop;
  const Vector3 q = q_from + std::max(0.0, s - margin / len) * d;
  if (record && recorded) {
    // Made at the contact (the sweep's pairs are complete there, past any
    // part a list showed free); it covers the landing point a margin back
    // as its distance has that room (Solve).
    record->q_S = q_from + s * d;
    record->valid = true;
  }
  return q;
}

// OutProject recording the leaf pairs near its landing point.
Vector3 OutProjectRecording(const ModelPair& pair, const Vector3& q_from, const Vector3& q_to,
                            double margin, bool* touched, LeafPairRecord* record) {
  return OutProject(pair, q_from, q_to, margin, touched, -1.0, nullptr, record);
}

}  // namespace

struct PolyDepthSolver::Impl {
  std::vector<ContactConstraint> constraints;
  MinNormScratch qp;
  std::vector<Start> starts;
  std::vector<double> landed_norms;  // cold: landing norms of the starts out-projected exactly
  std::vector<SupportPlaneStart> support_starts;
  std::vector<Vector3> inner_starts;  // cold: free probes below the best answer
  std::mt19937_64 rng;
  CandidatePairs candidates;  // leaf pairs near the last contact (warm start)
  LeafPairRecord record;      // leaf pairs near the last recorded out-projection
  DescentFront front;         // where the last full descent ended
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
  int list_builds = 0;          // this query's list builds and their wall time (us)
  double list_build_us = 0.0;
  // About how many leaf pairs the list holds (0 when there is none).
  double ListLeafPairs() const {
    if (!candidates.valid()) return 0.0;
    return static_cast<double>(candidates.entries().size()) *
           (candidates.grain() == CandidatePairs::Grain::kTwigPairs ? kTwigEntryLeafPairs : 1.0);
  }
  // Where the last list was dense, the next pairs small subtrees
  // (CandidatePairs::Grain): a dense patch's build is the query's work.
  CandidatePairs::Grain NextGrain() const {
    return ListLeafPairs() > kTwigListLeafPairs ? CandidatePairs::Grain::kTwigPairs
                                                : CandidatePairs::Grain::kLeafPairs;
  }
  // The deferred build under way, completed in this query and put in use:
  // the caller's idle time did not suffice and this query needs it (going
  // on without a list after a slow query made the next ones slow too: the
  // idle time of each went to nothing, a cascade on cow_armadillo's path).
  void FinishDeferredBuild(const ModelPair& pair) {
    const auto t0 = std::chrono::steady_clock::now();
    AdvanceDeferredBuild([] { return false; }, pair.counters);
    ++list_builds;
    list_build_us +=
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }
  void BuildList(const ModelPair& pair, const Vector3& q_center_S, double radius) {
    const auto t0 = std::chrono::steady_clock::now();
    candidates.Build(pair, q_center_S, radius, NextGrain());
    ++list_builds;
    list_build_us +=
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }
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
  int BasinProbeDirections(const Vector3& n, const Vector3& v_S) {
    int count = 0;
    for (const ContactConstraint& k : constraints) {
      if (count == kBasinNormalProbes) break;
      const double cos_n = k.n_S.dot(n);
      if (cos_n > kBasinNearCos || cos_n < kBasinFarCos) continue;
      bool same = false;
      for (int i = 0; i < count; ++i) same = same || basin_directions[i].dot(k.n_S) > kSameNormalCos;
      if (!same) basin_directions[count++] = k.n_S;
    }
    const Vector3 across = v_S - v_S.dot(n) * n;
    if (across.norm() > 0.0) {
      basin_directions[count++] = std::cos(kBasinMotionAngle) * n +
                                  std::sin(kBasinMotionAngle) * across.normalized();
    }
    return count;
  }
  // Whether the probe collides at q0 (along u), witnesses first (see
  // kBasinWitnessCos); a hit is kept for the next query's probe along u.
  bool BasinProbeCollides(const ModelPair& pair, const Vector3& q0, const Vector3& u) {
    CollisionWitness w = basin_witness;
    double best_cos = kBasinWitnessCos;
    for (int i = 0; i < num_basin_witnesses; ++i) {
      if (basin_witnesses[i].u_S.dot(u) > best_cos) {
        best_cos = basin_witnesses[i].u_S.dot(u);
        w = basin_witnesses[i].witness;
      }
    }
    bool hit = WitnessIntersects(pair, q0, &w);
    if (!hit) {
      // The triangle pairs of the answer's constraints q0 violates most
      // (c - n·q0 > 0), then the query's own pair, then the descent.
      std::array<std::pair<double, int>, kBasinViolatedWitnesses> top;
      top.fill({0.0, -1});
      for (int i = 0; i < static_cast<int>(constraints.size()); ++i) {
        const double v = constraints[i].c - constraints[i].n_S.dot(q0);
        if (v <= top.back().first) continue;
        int j = kBasinViolatedWitnesses - 1;
        for (; j > 0 && top[j - 1].first < v; --j) top[j] = top[j - 1];
        top[j] = {v, i};
      }
      std::array<CollisionWitness, kBasinViolatedWitnesses> violated;
      int num_violated = 0;
      for (; num_violated < kBasinViolatedWitnesses && top[num_violated].second >= 0;
           ++num_violated) {
        const ContactConstraint& k = constraints[top[num_violated].second];
        violated[num_violated] = {k.tri_P, k.tri_S};
      }
      w = query_witness;
      hit = InCollision(pair, q0, &w, violated.data(), num_violated);
    }
    if (hit) {
      basin_witness = w;
      next_basin_witnesses[num_next_basin_witnesses++] = {u, w};
    }
    return hit;
  }
  void EndBasinProbes() {
    std::swap(basin_witnesses, next_basin_witnesses);
    num_basin_witnesses = num_next_basin_witnesses;
    num_next_basin_witnesses = 0;
  }
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
  void JoinEarlierConstraints(const Vector3& q_c, double distance, bool creeping) {
    joined.assign(constraints.begin(), constraints.end());
    if (creeping) {
      for (const ContactConstraint& e : earlier) {
        if (e.n_S.dot(q_c) - e.c > distance) continue;
        const bool found = std::any_of(constraints.begin(), constraints.end(),
                                       [&](const ContactConstraint& c) {
                                         return c.kind == e.kind && c.feature_P == e.feature_P &&
                                                c.feature_S == e.feature_S;
                                       });
        if (!found) joined.push_back(e);
      }
    }
    earlier.assign(joined.begin(), joined.end());
  }
  double anchor_depth = 0.0;  // |q| the coherent answers are measured against (m)
  Vector3 anchor_n_S = Vector3::Zero();  // direction of the answer that set it
  double anchor_probe_depth = 0.0;  // |q| at the last probe along anchor_n_S (m)
  int check_next = -1;        // next direction of the running cross-check; -1: none
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
  // True once the search's share of the budget (kSearchShare) is spent and
  // some verified answer exists.
  bool OutOfBudget() {
    if (best_origin == Initializer::kNone || !BudgetSpent(kSearchShare)) return false;
    return stopped_early = true;
  }
  const std::function<bool()> stop_ccd = [this] { return OutOfBudget(); };
  // The query has a work or time budget (PolyDepthOptions::max_work,
  // max_time_us).
  bool Bounded() const { return work_limit > 0 || time_limit_us > 0.0; }
  // True once `share` of the budget is spent (never without a budget).
  bool BudgetSpent(double share = 1.0) const {
    return (work_limit > 0 && counters.box_tests + counters.triangle_tests >= share * work_limit) ||
           (time_limit_us > 0 &&
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t_start)
                    .count() >= share * time_limit_us);
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

  // A coherent iterate that has left the list's reach (a basin switch
  // moving the answer by millimetres) would localise and out-project by full
  // descents from here on: the list moves to it, once per query (the next
  // query starts near there too). cow_armadillo: p99 work -13%, same
  // answers; a second move per query made knot1_bunny's deepest queries 15%
  // dearer, and moving it to step 0's targets too raised every p99 and max
  // (those targets go out and back in one query).
  void FollowWithList(const ModelPair& pair, const PolyDepthOptions& opt, double size,
                      const Vector3& q_S) {
    const double contact_distance = opt.contact_tol * size;
    if (!list_follows_iterates || !candidates.valid() ||
        candidates.Covers(pair, q_S, q_S, kListIterationRoom * contact_distance))
      return;
    const double radius = opt.candidate_radius * size + kListIterationRoom * contact_distance;
    if (opt.defer_list_builds) {  // after the answer, around it
      WantBuild(Vector3::Zero(), radius);
      list_follows_iterates = false;
      return;
    }
    BuildList(pair, q_S, radius);
    list_follows_iterates = false;
  }

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
               Initializer origin, StartAbandon* abandon = nullptr) {
  Impl& s = *this;
  const double tol = opt.convergence_tol * size;
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  s.Offer(q_c, origin);
  double norm_c = q_c.norm();
  bool off_contact = false;  // q_c is a reached in-projection target, not a landing
  bool localised_here = false;  // `constraints` hold q_c's localisation already
  if (abandon) abandon->Update(norm_c);
  ++s.iterated_starts;
  for (int it = 0; it < opt.max_iterations; ++it) {
    if (s.OutOfBudget()) break;
    if (s.JoinsAnEarlierStart(q_c, norm_c)) break;
    if (s.join_distance > 0.0) s.trail.push_back({q_c, 1e300});
    ++s.iterations;
    if (origin == Initializer::kMotionCoherence) s.FollowWithList(pair, opt, size, q_c);
    // Localise the contact space at q_c and in-project toward the query
    // (the localisation kept at the best answer is q_c's when a search
    // goes on from there: the incremental update's last free point, whose
    // localisation was repeated, up to 2.6k tests where no list covered it;
    // haptic_work total work -1.3%, cow_armadillo p99 -5%).
    if (localised_here) {
      localised_here = false;  // a reached target's test localised it (below)
    } else if (q_c == s.best_constraints_q_S) {
      s.constraints = s.best_constraints;
    } else if (CollectContactConstraintsIfSurfacesFree(pair, q_c, contact_distance,
                                                       &s.constraints, nullptr, &s.record)) {
      // The same pass tests the surfaces: when q_c ends the search, the
      // answer's verification needs only the containment test.
      s.surfaces_free_q_S = q_c;
    } else {
      // A landing whose surfaces cross (round-off): localise it in full,
      // and let the verification judge it.
      CollectContactConstraints(pair, q_c, contact_distance, &s.constraints, &s.record);
    }
    s.constraints_q_S = q_c;
    if (q_c == s.best_q_S) {
      s.best_constraints = s.constraints;
      s.best_constraints_q_S = q_c;
    }
    if (s.constraints.empty()) {
      if (!off_contact) break;
      // Reached free and nothing within reach there: land on the contact
      // space toward the query.
      off_contact = false;
      bool touched = false;
      const Vector3 q_next =
          OutProjectRecording(pair, q_c, Vector3::Zero(), margin, &touched, &s.record);
      if (!touched) break;
      q_c = q_next;
      norm_c = q_c.norm();
      s.Offer(q_c, origin);
      continue;
    }
    off_contact = false;
    // The local model: the localisation's constraints, and in a long
    // coherent search also the earlier iterates' that are still about as
    // near (by plane distance; s.JoinEarlierConstraints).
    s.JoinEarlierConstraints(q_c, contact_distance,
                             origin == Initializer::kMotionCoherence &&
                                 opt.creep_join_iterations > 0 && it >= opt.creep_join_iterations);
    // Aim strictly inside free space: an exactly touching target is
    // ambiguous under round-off, a target `margin` clear is not. (The local
    // model only: `constraints` stay as localised, so a later model built
    // from them, e.g. the cold polish's, adds the margin once.)
    for (ContactConstraint& c : s.joined) c.c += margin;
    const Vector3 q_new = MinNormPoint(s.joined, tol, &s.qp).q;
    if (q_new.norm() >= norm_c - tol) break;  // q_c is locally optimal
    // A short step's target is usually free (the local model held the
    // contact it reaches): tested and localised there in one pass, it needs
    // no out-projection (see kTargetFirstSteps).
    if ((q_new - q_c).norm() < kTargetFirstSteps * contact_distance &&
        s.LocaliseIfFree(pair, q_new, contact_distance, nullptr)) {
      localised_here = true;
      off_contact = true;
      q_c = q_new;
      norm_c = q_c.norm();
      s.Offer(q_c, origin);
      if (abandon && abandon->Update(norm_c)) break;
      continue;
    }
    // Move toward q_new, landing on the first contact on the way.
    bool touched = false;
    Vector3 q_next = OutProjectRecording(pair, q_c, q_new, margin, &touched, &s.record);
    // Stopped by the budget, the sweep's free point is not taken: the
    // answer stays at q_c, whose localisation the result needs and has (at
    // the sweep's point it would cost a descent of both hierarchies, the
    // stopped sweep leaving no record: 2k tests past a 7k budget on
    // cow_armadillo, for a gain of micrometres).
    if (s.stopped_early && q_c == s.best_constraints_q_S) break;
    if (!touched) {
      // The target is free (the sweep to it from a free start met nothing)
      // and lies on the local model's boundary, usually on the contact space
      // itself: the next step localises there (a walk of the pairs the sweep
      // recorded) instead of sweeping it back toward the query first (a CCD
      // the whole depth long that lands a margin away: 2-6k tests on the
      // haptic paths' deep queries). Only where nothing is within reach
      // there does it out-project (above). Same errors on 72 reference
      // cases of 6 real pairs (bench_pd random); work on 96 cold
      // random cases of 4 real pairs -3 to -7%, haptic_work's p99 and max
      // work down up to 13% (cow_armadillo max 21126 -> 18459).
      off_contact = true;
    }
    const double norm_next = q_next.norm();
    const bool improved = norm_next < norm_c - tol;
    q_c = q_next;
    norm_c = norm_next;
    s.Offer(q_c, origin);
    if (!improved) break;
    if (abandon && abandon->Update(norm_c)) break;
  }
  return q_c;
}

  // The unit direction that moves the probe off every one of `cs` at once
  // (the shortest x with n_i·x >= 1 for all, normalised), and in *clearance
  // the least rate min_i n_i·d at which it does; zero vector and clearance
  // <= 0 when no direction clears them all (the probe is wedged).
  std::vector<ContactConstraint> pocket_constraints;  // the pocket check's (Solve)
  Vector3 ClearingDirection(const std::vector<ContactConstraint>& cs, double tol,
                            double* clearance) {
    unit_constraints.assign(cs.begin(), cs.end());
    for (ContactConstraint& c : unit_constraints) c.c = 1.0;
    const Vector3 x = MinNormPoint(unit_constraints, tol, &qp).q;
    *clearance = 0.0;
    if (!(x.norm() > 0.0) || !x.allFinite()) return Vector3::Zero();
    const Vector3 d = x.normalized();
    double least = 1e300;
    for (const ContactConstraint& c : cs) least = std::min(least, c.n_S.dot(d));
    *clearance = least;
    return least > 0.0 ? d : Vector3::Zero();
  }

  // Localises at q_S and tests it free in the same pass (the surfaces, then
  // the models' containment). Free: true, `constraints` q_S's and q_S
  // verified. Not: false, `constraints` no configuration's (the pass stopped
  // at the first intersecting triangle pair, recorded in *witness if given).
  bool LocaliseIfFree(const ModelPair& pair, const Vector3& q_S, double distance,
                      CollisionWitness* witness) {
    constraints_q_S = Vector3::Constant(1e300);
    if (!CollectContactConstraintsIfSurfacesFree(pair, q_S, distance, &constraints, witness,
                                                 &record) ||
        AnyComponentInside(pair, q_S))
      return false;
    constraints_q_S = q_S;
    verified_q_S = q_S;
    return true;
  }

  void Offer(const Vector3& q_S, Initializer origin) {
    const double n = q_S.norm();
    if (n < best_norm) {
      best_norm = n;
      best_q_S = q_S;
      best_origin = origin;
    }
  }
};

PolyDepthSolver::PolyDepthSolver(std::shared_ptr<const CollisionModel> probe,
                                 std::shared_ptr<const CollisionModel> scene,
                                 PolyDepthOptions options)
    : probe_(std::move(probe)), scene_(std::move(scene)), options_(options),
      impl_(std::make_unique<Impl>()) {
  impl_->rng.seed(options_.seed);
  impl_->constraints.reserve(1024);
  impl_->best_constraints.reserve(1024);
  impl_->previous_constraints.reserve(1024);
  impl_->unit_constraints.reserve(1024);
  impl_->pocket_constraints.reserve(1024);
  impl_->joined.reserve(1024);
  impl_->earlier.reserve(1024);
  impl_->starts.reserve(128);
  impl_->trail.reserve(512);
  impl_->qp.unique.reserve(1024);
  impl_->qp.lambda.reserve(1024);
}

PolyDepthSolver::~PolyDepthSolver() = default;

PolyDepthSolver::Preparation PolyDepthSolver::PrepareNext(const std::function<bool()>& pause) {
  Impl& s = *impl_;
  Preparation p;
  if (!s.next_candidates.building()) return p;
  const auto t0 = std::chrono::steady_clock::now();
  ProximityCounters counters;
  const std::function<bool()> never = [] { return false; };
  p.done = s.AdvanceDeferredBuild(pause ? pause : never, &counters);
  p.lists_completed = p.done ? 1 : 0;
  p.box_tests = counters.box_tests;
  p.time_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  return p;
}

void PolyDepthSolver::ResetWarmStart() {
  impl_->candidates.Invalidate();
  impl_->next_candidates.Invalidate();
  impl_->previous_constraints.clear();
  impl_->witness = CollisionWitness{};
  impl_->query_witness = CollisionWitness{};
  impl_->basin_witness = CollisionWitness{};
  impl_->num_basin_witnesses = 0;
  impl_->has_previous_replaced = false;
  impl_->anchor_depth = 0.0;
  impl_->check_next = -1;
  impl_->has_previous = false;
  impl_->has_previous_free = false;
}



PenetrationResult PolyDepthSolver::Solve(const Isometry3& X_WP, const Isometry3& X_WS,
                                         bool coherent) {
  Impl& s = *impl_;
  s.t_start = std::chrono::steady_clock::now();
  PenetrationResult result;
  ModelPair pair(*probe_, *scene_, X_WP, X_WS);
  pair.candidates = &s.candidates;
  s.record.Invalidate();
  // The localisation's distance plus room for the landing's margin (OutProject).
  s.record.distance = (options_.contact_tol + 2.0 * options_.separation_margin) * pair.size();
  pair.recorded = &s.record;
  s.front.Invalidate();  // within a query only (descent_front.h)
  pair.front = &s.front;
  s.counters = ProximityCounters{};
  pair.counters = &s.counters;
  s.work_limit = options_.max_work;
  s.time_limit_us = options_.max_time_us;
  s.stopped_early = false;
  s.landings_cut = false;
  // Bounded time: once the budget is spent and a verified answer exists, a
  // CCD under way stops too, at a point it knows free (translational_ccd.h).
  if (s.Bounded()) pair.stop_ccd = &s.stop_ccd;
  s.list_builds = 0;
  s.list_build_us = 0.0;
  const double size = pair.size();
  const double margin = options_.separation_margin * size;
  const double contact_distance = options_.contact_tol * size;
  s.iterations = 0;
  s.iterated_starts = 0;
  s.constraints_q_S = Vector3::Constant(1e300);
  s.best_constraints_q_S = Vector3::Constant(1e300);
  // Localises at the best answer unless `constraints` hold it already; the
  // same localisation kept from Iterate when there is one (same pair, same
  // configuration: the same constraints).
  auto localise_at_best = [&] {
    if (s.constraints_q_S == s.best_q_S) return;
    if (s.best_constraints_q_S == s.best_q_S)
      s.constraints = s.best_constraints;
    else
      CollectContactConstraints(pair, s.best_q_S, contact_distance, &s.constraints, &s.record);
    s.constraints_q_S = s.best_q_S;
  };
  auto finish = [&] {
    result.box_tests = s.counters.box_tests;
    result.triangle_tests = s.counters.triangle_tests;
    const auto& k = s.counters.by_kind;
    result.work.collision = k[static_cast<int>(QueryKind::kCollision)];
    result.work.localisation = k[static_cast<int>(QueryKind::kLocalisation)];
    result.work.out_projection = k[static_cast<int>(QueryKind::kOutProjection)];
    result.work.list_builds = k[static_cast<int>(QueryKind::kListBuild)];
    result.work.other = s.counters.total() - result.work.collision - result.work.localisation -
                        result.work.out_projection - result.work.list_builds;
    result.list_builds = s.list_builds;
    result.list_build_us = s.list_build_us;
    result.time_us = std::chrono::duration<double, std::micro>(
                         std::chrono::steady_clock::now() - s.t_start).count();
    return result;
  };

  const bool warm = coherent && options_.warm_start;
  s.list_follows_iterates = warm;
  // How far any probe point moved since the previous frame (m).
  // (`turn`: its rotation's share, angle times the probe's radius.)
  const bool moved_from_previous = warm && (s.has_previous || s.has_previous_free);
  const double turn =
      moved_from_previous
          ? RotationAngleBetween(s.previous_X_SP.R_SP, pair.X_SP.R_SP) * probe_->radius()
          : 0.0;
  const double motion =
      moved_from_previous ? (pair.X_SP.p_SP - s.previous_X_SP.p_SP).norm() + turn : 0.0;
  // Incremental update, step one: the previous answer's feature pairs,
  // re-evaluated at the new pose, predict the new local contact model; its
  // in-projection q_pred predicts the answer (no geometry query needed).
  bool have_prediction = false;
  Vector3 q_pred = Vector3::Zero();
  // The prediction is a first-order model of a small motion: after a jump
  // (more than kPredictionMotion of the pair's size since the last answer)
  // the contact may have changed shape and the restarts below decide.
  constexpr double kPredictionMotion = 5e-3;
  if (warm && s.has_previous && !s.previous_constraints.empty() &&
      motion <= kPredictionMotion * size) {
    RefreshContactConstraints(pair, s.previous_q_S, s.previous_constraints, &s.constraints);
    for (ContactConstraint& c : s.constraints) c.c += margin;
    q_pred = MinNormPoint(s.constraints, options_.convergence_tol * size, &s.qp).q;
    have_prediction = q_pred.allFinite();
  }
  // Keep the leaf-pair list around where this query will work: the
  // prediction, else the configuration we restart from, with room for the
  // motion and the iterations' contact distance. A new list is built only
  // once the query is known to collide (below), and not for a contact
  // regained from a free frame: a free query needs none (building one there
  // cost a lift-off's free poses up to 27k tests each on fandisk_elephant,
  // against ~1.5k for the collision test's own descent), and a regained
  // contact's list would have to reach back over the whole motion since the
  // free frame (its out-projection records the leaf pairs it needs, and an
  // iterate that leaves the old list moves it there, FollowWithList).
  bool build_pending = false;
  Vector3 build_center = Vector3::Zero(), build_lead = Vector3::Zero();
  double build_radius = 0.0;
  Vector3 list_center = Vector3::Zero();  // where the query's list must reach, and how far
  double list_need = 0.0;
  s.build_wanted = false;
  if (warm && (s.has_previous || s.has_previous_free)) {
    const double need =
        (have_prediction ? 0.0 : 2.0 * motion) + kListIterationRoom * contact_distance;
    const Vector3 center = have_prediction ? q_pred : s.previous_q_S;
    list_center = center;
    list_need = need;
    if (need > kListMaxNeed * options_.candidate_radius * size) {
      // A jump: a list wide enough to cover it would hold a large part of
      // both meshes' leaf pairs (one such build took minutes on 52k x 75k
      // triangles). The queries descend the hierarchies instead.
      s.candidates.Invalidate();
      s.next_candidates.Invalidate();
    } else if (s.has_previous && !s.candidates.Covers(pair, center, center, need)) {
      // Sliding: centre the new list ahead along the motion, where the
      // coming queries will be, so it lasts longer than one centred here.
      const Vector3 v = pair.X_SP.p_SP - s.previous_X_SP.p_SP;
      double reach = std::clamp(kListTicks * motion, options_.candidate_radius * size,
                                kListMaxReach * options_.candidate_radius * size);
      // A dense contact (a broad flat patch) holds many leaf pairs per
      // radius squared: judged by the list it replaces, the reach shrinks to
      // about kListMaxEntries entries (not below candidate_radius). Such a
      // list costs about five box tests per entry to build, and the CCD
      // counts every entry of the prefix it walks.
      const double entries = s.ListLeafPairs();
      if (entries > kListMaxEntries && s.candidates.radius() > 0.0) {
        const double capped =
            s.candidates.radius() * std::sqrt(kListMaxEntries / entries) - need;
        reach = std::max(options_.candidate_radius * size, std::min(reach, capped));
      }
      const double lead = have_prediction && v.norm() > 0.0 ? kListLead * reach : 0.0;
      build_lead = lead > 0.0 ? Vector3(lead * v.normalized()) : Vector3::Zero();
      build_center = center + build_lead;
      build_radius = reach + need;
      build_pending = true;
    }
  }

  // The collision test at the query walks the list where it still covers
  // the query pose, else descends the hierarchies (stopping at the first
  // intersecting triangle pair; the last one is tried first).
  result.in_collision = InCollision(pair, Vector3::Zero(), &s.query_witness);
  if (result.in_collision && build_pending) {
    if (options_.defer_list_builds) {
      if (s.next_candidates.BuildWillCover(pair, list_center, list_need)) {
        s.FinishDeferredBuild(pair);
      } else {
        s.WantBuild(build_lead, build_radius);
      }
    } else {
      s.BuildList(pair, build_center, build_radius);
    }
  }
  if (!result.in_collision) {
    // Remember this free pose: the next contact starts from it.
    s.has_previous = false;
    s.has_previous_free = true;
    s.previous_X_SP = pair.X_SP;
    s.previous_constraints.clear();
    s.anchor_depth = 0.0;
    s.check_next = -1;
    return finish();
  }
  s.best_norm = 1e300;
  s.best_origin = Initializer::kNone;
  s.verified_q_S = Vector3::Constant(1e300);
  s.surfaces_free_q_S = Vector3::Constant(1e300);

  // 0. Incremental update, step two: from the prediction, localise and test
  // the surfaces in one pass; while the configuration is free, in-project on
  // what was found there and try the result the same way (a free target
  // needs no out-projection). Stops at a local optimum, or hands a colliding
  // target to the out-projecting iteration from the last free point.
  if (have_prediction) {
    const double tol = options_.convergence_tol * size;
    Vector3 q = q_pred;
    for (int k = 0; k < options_.max_iterations; ++k) {
      if (s.OutOfBudget()) break;
      if (!s.LocaliseIfFree(pair, q, contact_distance, &s.witness)) break;
      if (s.constraints.empty()) {
        // Free but off the contact space (the probe moved away from the
        // contact): land on it toward the query, then go on from there
        // (recording: the localisation there walks the sweep's pairs; it
        // descended both hierarchies again, 2.5k tests on knot1_bunny's
        // deepest queries).
        bool touched = false;
        const Vector3 q_c =
            OutProjectRecording(pair, q, Vector3::Zero(), margin, &touched, &s.record);
        if (!touched) break;
        if (!(q_c.norm() < q.norm() - tol)) {
          // It touches where it stands, yet no feature pair there gives a
          // half-space (a degenerate contact: parallel edges, a pair on no
          // face of the Minkowski difference): q is this step's answer.
          // Landing again would land on itself: one query did so 40 times,
          // 36k tests (cow_armadillo on a seeded path).
          s.Offer(q, Initializer::kMotionCoherence);
          break;
        }
        q = q_c;
        continue;
      }
      ++s.iterations;
      s.Offer(q, Initializer::kMotionCoherence);
      // Each point offered here is the best answer so far (the first, then
      // strictly shorter): keep its localisation for Iterate (which goes on
      // from the last one when the next target collides) and the end.
      s.best_constraints = s.constraints;
      s.best_constraints_q_S = q;
      for (ContactConstraint& c : s.constraints) c.c += margin;
      const Vector3 q_new = MinNormPoint(s.constraints, tol, &s.qp).q;
      if (!(q_new.norm() < q.norm() - tol)) break;  // q is locally optimal
      q = q_new;
    }
    // The last target collided: continue from the last free point the usual
    // way (its out-projection lands on the contact space before the target).
    if (s.best_origin != Initializer::kNone && q != s.verified_q_S)
      s.Iterate(pair, options_, size, s.verified_q_S, Initializer::kMotionCoherence);
  }

  // 1. Motion coherence: step off the previous answer along its normal by
  // about the motion since then, verify freedom, and iterate from there.
  if (warm && s.has_previous && s.best_origin == Initializer::kNone) {
    // Free candidates, nearest first: the previous answer stepped off along
    // its normal by about the motion; the previous answer with the motion's
    // translation undone (the probe back where it was free, off by the
    // rotation only), stepped off a little.
    const Vector3 back = s.previous_X_SP.p_SP - pair.X_SP.p_SP;
    const double step = motion + contact_distance, back_step = turn + contact_distance;
    const std::array<Vector3, 7> candidates = {
        s.previous_q_S + step * s.previous_n_S,
        s.previous_q_S + back + back_step * s.previous_n_S,
        s.previous_q_S + 4.0 * step * s.previous_n_S,
        s.previous_q_S + back + 4.0 * back_step * s.previous_n_S,
        s.previous_q_S + back + 16.0 * back_step * s.previous_n_S,
        s.previous_q_S + 16.0 * step * s.previous_n_S,
        s.previous_q_S + 64.0 * step * s.previous_n_S};
    auto try_from = [&](const Vector3& q0) {
      if (InCollision(pair, q0)) return false;
      // Verified free: an answer already (an upper bound), so a bounded
      // query may stop the out-projection from it (pair.stop_ccd).
      s.verified_q_S = q0;
      s.Offer(q0, Initializer::kMotionCoherence);
      bool touched = false;
      const Vector3 q_c =
          OutProjectRecording(pair, q0, Vector3::Zero(), margin, &touched, &s.record);
      // Stopped by the budget, its free point is not taken (as in Iterate):
      // q0 is tested in full, the point short of the contact is not.
      if (touched && !s.stopped_early)
        s.Iterate(pair, options_, size, q_c, Initializer::kMotionCoherence);
      return true;
    };
    const auto far = candidates.begin() + kNearStepOffs;
    bool started = std::any_of(candidates.begin(), far, try_from);
    // A feature leaning over the previous answer's direction blocks those
    // steps: step off along the direction that clears all its feature pairs,
    // 1 and 4 steps before the far step-offs above (16 and 64 steps), which
    // land far out and iterate back down (cow_armadillo on haptic_work's
    // first path: 64 steps out, landing at 7x the answer's length and 8
    // iterations back, 19.0k tests; from the clearing direction 3.9k, and
    // an answer 9% shorter).
    double clearance = 0.0;
    const Vector3 d = started ? Vector3::Zero()
                              : s.ClearingDirection(s.previous_constraints,
                                                    options_.convergence_tol, &clearance);
    // From q along u by k steps of 1/per along u, then with the motion
    // undone by k back steps.
    auto step_off = [&](const Vector3& q, const Vector3& u, double k, double per) {
      return try_from(q + (k * step / per) * u) || try_from(q + back + (k * back_step / per) * u);
    };
    auto try_clearing = [&](double k) {
      return clearance > 0.0 && step_off(s.previous_q_S, d, k, clearance);
    };
    started = started || try_clearing(1.0) || try_clearing(4.0) ||
              std::any_of(far, candidates.end(), try_from) ||
              try_clearing(16.0);
    started = started || try_clearing(64.0);
    // The previous answer came from a neighbour-basin probe (step 2e) and
    // that basin closed over it: go on from the answer it replaced
    // (fandisk_elephant on haptic_work's seed 20240618, pose 2438: every
    // step-off of the probe's answer collided and the query restarted cold,
    // 80.6k tests, 4.1 ms).
    for (double k : {1.0, 4.0, 16.0}) {
      if (started || !s.has_previous_replaced) break;
      started = step_off(s.previous_replaced_q_S, s.previous_replaced_q_S.normalized(), k, 1.0);
    }
  }

  // 1b. Coming from a free frame: put the probe back where it was then (a
  // free place a short way back along the motion) and out-project from there.
  if (warm && !s.has_previous && s.has_previous_free && s.best_origin == Initializer::kNone) {
    const Vector3 back = s.previous_X_SP.p_SP - pair.X_SP.p_SP;
    const double len = back.norm();
    if (len > 0.0) {
      double offset = contact_distance;
      for (int attempt = 0; attempt < 3; ++attempt, offset *= 4.0) {
        const Vector3 q0 = back + offset * (back / len);
        if (InCollision(pair, q0)) continue;
        s.verified_q_S = q0;
        s.Offer(q0, Initializer::kMotionCoherence);  // verified free (see try_from above)
        bool touched = false;
        const Vector3 q_c =
            OutProjectRecording(pair, q0, Vector3::Zero(), margin, &touched, &s.record);
        if (touched) {
          s.Iterate(pair, options_, size, q_c, Initializer::kMotionCoherence);
        } else {
          // Free all the way: the query only touches (the CCD counts no
          // contact at the very end). Back off along the motion by the
          // margin; without this the cold starts answered from outside the
          // scene's hull, through the wall (tests/pd_core/test_hard_cases.cc).
          const Vector3 q_b = margin * (back / len);
          if (!InCollision(pair, q_b)) s.Iterate(pair, options_, size, q_b, Initializer::kMotionCoherence);
        }
        break;
      }
    }
  }

  // 2. Cold starts: the fallback when coherence found nothing.
  auto cold_starts = [&] {
    s.starts.clear();
    // Random directions drawn afresh from the seed (same query, same answer).
    s.rng.seed(options_.seed);
    const int num_clear = options_.num_maximally_clear;
    const int num_iterated =
        s.Bounded() ? std::min(options_.num_iterated_starts, options_.num_iterated_starts_bounded)
                    : options_.num_iterated_starts;
    ComputeSupportPlaneStarts(pair, std::max(num_clear, kMinSupportDirections), &s.support_starts);
    // Maximally clear: the best support-plane separations of the two models.
    for (int i = 0; i < std::min<int>(num_clear, s.support_starts.size()); ++i)
      s.starts.push_back({s.support_starts[i].q_S, Initializer::kMaximallyClear});
    if (options_.use_centroid) {
      const Vector3 d = pair.X_SP * probe_->centroid() - scene_->centroid();
      if (d.norm() > 1e-9 * size)
        s.starts.push_back({SupportPlaneTranslation(pair, d.normalized()),
                            Initializer::kCentroidDifference});
    }
    std::normal_distribution<double> gauss;
    for (int i = 0; i < options_.num_random; ++i) {
      Vector3 u(gauss(s.rng), gauss(s.rng), gauss(s.rng));
      if (u.norm() < 1e-9) continue;
      s.starts.push_back({SupportPlaneTranslation(pair, u.normalized()), Initializer::kRandom});
    }
    // Out-project every start once, then iterate from the closest few.
    // Once num_iterated starts have landed, a start's CCD stops as soon as
    // it has a contact before where it would land closer than the
    // num_iterated-th closest so far: that start is not iterated, so its
    // exact landing point is not needed (the iterated ones are the same).
    s.landed_norms.clear();
    double best_landing = 1e300;
    for (size_t k = 0; k < s.starts.size(); ++k) {
      Start& st = s.starts[k];
      // Bounded: the landings take at most kColdLandingShare of the search's
      // share of the budget once one has landed; the rest iterates the
      // closest so far.
      if (!s.landed_norms.empty() && s.BudgetSpent(kColdLandingShare * kSearchShare)) {
        s.landings_cut = true;
        s.starts.resize(k);
        break;
      }
      st.contact_norm = 1e300;
      ++result.starts;
      const double len = st.q_S.norm();
      double s_stop = -1.0;
      if (len > 0.0 && num_iterated > 0 && !s.landed_norms.empty()) {
        // A landing farther than the num_iterated-th closest so far, or
        // than cold_start_gate above the closest (it lands above the best
        // answer by more than the gate: not iterated), needs no exact
        // landing point.
        double threshold = (1.0 + options_.cold_start_gate) * best_landing;
        if (static_cast<int>(s.landed_norms.size()) >= num_iterated) {
          std::nth_element(s.landed_norms.begin(), s.landed_norms.begin() + (num_iterated - 1),
                           s.landed_norms.end());
          threshold = std::min(threshold, s.landed_norms[num_iterated - 1]);
        }
        // Landing at s lies (1 - s + margin / len) |q_S| from the query
        // (OutProject); contacts before s_stop land farther than the
        // threshold (by a relative 1e-9, against round-off).
        s_stop = 1.0 + margin / len - threshold / len - 1e-9;
      }
      // Colliding where it would land at the threshold, it lands farther:
      // out of the running, settled by a collision test (~140 tests) instead
      // of a sweep from outside the models (~1k). Same answers; on 24 random
      // cases of 13 real pairs the cold median -40-53% (cow_cow 6.2 -> 3.7
      // ms, dragon_dragon 12.8 -> 6.0 ms). No collision witness: the last
      // direction's intersecting pair and its neighbours (16 triangle tests)
      // never intersect along the next (1.9% fewer tests without). The
      // models' inner spheres settle most of these (and the inner probes'
      // tests) before any BVH test: same answers on 24 random cases of 13
      // real pairs, collision work -33-65%, medians -5-24% (a mesh that is
      // not closed has no spheres: dragon_dragon unchanged).
      if (s_stop > 0.0 && s_stop < 1.0 &&
          InCollisionExpectingDepth(pair, (1.0 - s_stop) * st.q_S))
        continue;
      bool touched = false, exact = true;
      st.contact_q_S =
          OutProject(pair, st.q_S, Vector3::Zero(), margin, &touched, s_stop, &exact);
      if (!touched) continue;
      st.contact_norm = st.contact_q_S.norm();
      if (!exact) continue;
      s.landed_norms.push_back(st.contact_norm);
      best_landing = std::min(best_landing, st.contact_norm);
      // A landing is free (the CCD's): the answer so far, should the
      // budget end the query before any iteration.
      s.Offer(st.contact_q_S, st.origin);
    }
    std::sort(s.starts.begin(), s.starts.end(),
              [](const Start& a, const Start& b) { return a.contact_norm < b.contact_norm; });
    // With a screening tolerance the starts iterate only until their steps
    // gain less than it; the best of them then goes on to convergence_tol.
    const bool screen = options_.cold_screen_tol > options_.convergence_tol;
    PolyDepthOptions screen_options = options_;
    if (screen) screen_options.convergence_tol = options_.cold_screen_tol;
    for (int i = 0; i < std::min<int>(num_iterated, s.starts.size()); ++i) {
      if (s.starts[i].contact_norm >= 1e300) break;
      if (i > 0 && s.OutOfBudget()) break;
      // After the first, only starts landing near the best answer so far
      // (the starts are sorted by landing).
      if (i > 0 && s.starts[i].contact_norm > (1.0 + options_.cold_start_gate) * s.best_norm)
        break;
      // After the first, a start stops once it cannot beat the best answer.
      StartAbandon abandon(s.best_norm);
      s.EndStart(s.Iterate(pair, screen_options, size, s.starts[i].contact_q_S,
                           s.starts[i].origin,
                           i > 0 && options_.cold_abandon ? &abandon : nullptr));
    }
    if (screen && s.best_origin != Initializer::kNone && !s.OutOfBudget())
      s.EndStart(s.Iterate(pair, options_, size, s.best_q_S, s.best_origin));
    // Probes from the inside: free configurations shallower than the best
    // answer, out-projected toward the query and iterated like the others.
    auto iterate_inner_starts = [&] {
      for (const Vector3& q0 : s.inner_starts) {
        if (s.OutOfBudget()) break;
        bool touched = false;
        ++result.starts;
        const Vector3 q_c = OutProject(pair, q0, Vector3::Zero(), margin, &touched);
        if (!touched) continue;
        StartAbandon abandon(s.best_norm);
        s.EndStart(s.Iterate(pair, options_, size, q_c, Initializer::kMaximallyClear,
                             options_.cold_abandon ? &abandon : nullptr));
      }
    };
    // The shell: the other basins just shallower than the answer.
    if (options_.cold_shell_probes > 0 && s.best_origin != Initializer::kNone &&
        !s.OutOfBudget()) {
      s.inner_starts.clear();
      InnerProbeStarts(pair, s.best_norm, options_.cold_shell_probes, {kShellRadius},
                       kShellIterated, &s.inner_starts, s.stop_ccd);
      iterate_inner_starts();
    }
    // Then deeper inside the (possibly shallower) answer: pockets.
    if (options_.cold_inner_probes > 0 && s.best_origin != Initializer::kNone &&
        !s.OutOfBudget()) {
      // Deeper fractions first: the first free ones are the most promising.
      s.inner_starts.clear();
      InnerProbeStarts(pair, s.best_norm, options_.cold_inner_probes, {0.7, 0.9}, 2,
                       &s.inner_starts, s.stop_ccd);
      // Deeper still, on a denser set of directions, after those (which
      // they must not displace: see cold_deep_probes).
      if (options_.cold_deep_probes > 0)
        InnerProbeStarts(pair, s.best_norm, kDeepProbeDirections, {0.3, 0.5},
                         options_.cold_deep_probes, &s.inner_starts, s.stop_ccd);
      iterate_inner_starts();
    }
    // The best answer's local model may put its optimum a little shorter
    // than where its start stopped: within convergence_tol, a fraction of
    // the pair's size, coarse next to a shallow answer (a needle lying 1 mm
    // into a face ended 0.4% deep of it with one iterated start). Taken if
    // free.
    if (s.best_origin != Initializer::kNone && !s.OutOfBudget()) {
      localise_at_best();
      s.joined.assign(s.constraints.begin(), s.constraints.end());
      for (ContactConstraint& c : s.joined) c.c += margin;
      const Vector3 q_new = MinNormPoint(s.joined, 1e-9 * size, &s.qp).q;
      if (q_new.norm() < s.best_norm - 1e-9 * size &&
          (q_new - s.best_q_S).norm() < kTargetFirstSteps * contact_distance &&
          s.LocaliseIfFree(pair, q_new, contact_distance, nullptr))
        s.Offer(q_new, s.best_origin);
    }
  };
  const bool warm_found = s.best_origin != Initializer::kNone;
  result.warm_start_failed = warm && (s.has_previous || s.has_previous_free) && !warm_found;
  // 2b. Cross-check of a coherent answer that has grown much deeper than
  // where it was last anchored (a followed local optimum can drift far from
  // the PD): probe free space around the query inside the coherent answer's
  // length, a few directions per query. A probe that is free out-projects
  // toward the query; landing shorter, it is iterated and becomes the answer
  // the next queries follow. Any shorter answer is reachable this way from
  // the direction it lies in, so the check needs no far-away starts (a burst
  // of cold starts here cost 10-30 ms).
  // (A bounded query out of budget leaves both to the next query.)
  const bool budget_left = !(warm_found && s.OutOfBudget());
  const bool check =
      warm_found && budget_left && (s.check_next >= 0 ||
                     (s.anchor_depth > 0.0 &&
                      s.best_norm > kReanchorGrowth * s.anchor_depth + kReanchorFloor * size));
  // 2c. Between checks, a coherent answer that has turned away from the
  // anchor's direction while growing deeper gets one probe back along that
  // direction: the basin it follows is drifting, and a shallower one usually
  // opens back toward where the answer was (fandisk_elephant: the reference
  // lay 7-15 degrees from the anchor's direction while the followed answer
  // turned 14-48 degrees away and grew 1.22 -> 2.02 mm before the check's
  // 1.2x trigger; mean error on the bench's poses 6.1% -> 0.5%).
  const bool turned =
      warm_found && budget_left && !check && s.anchor_depth > 0.0 &&
      s.best_norm > kAnchorProbeGrowth * std::max(s.anchor_depth, s.anchor_probe_depth) &&
      s.best_q_S.dot(s.anchor_n_S) < kAnchorProbeCos * s.best_norm;
  // 2e (below): otherwise, probes along the answer's own contact normals.
  // 2d. Before 2b or 2c: the answer's own contact may prove it within
  // kProvedSlack of the PD (depth_lower_bound.h).
  auto answer_proved = [&] {
    localise_at_best();
    return ProvesDepthAtLeast(pair, s.constraints, s.best_norm / (1.0 + kProvedSlack));
  };
  if (!warm_found) {
    s.trail.clear();
    s.trail_start = 0;
    s.join_distance = options_.cold_join * size;
    cold_starts();
    s.join_distance = 0.0;
  } else if ((check || turned) && answer_proved()) {
    // Every probe would collide: none run; a running check ends here and the
    // anchor moves to the answer.
    if (check) {
      s.check_next = -1;
      s.SetAnchor(s.best_q_S);
    } else {
      s.anchor_probe_depth = s.best_norm;
    }
  } else if (budget_left) {
    // 2b, 2c or 2e: probes at kCheckRadius of the answer's length. A free
    // probe is out-projected toward the query and iterated if it lands
    // shorter; the following queries' coherent updates go on from there.
    if (check && s.check_next < 0) {
      s.check_next = 0;
      s.check_start_q_S = s.best_q_S;
    }
    const Vector3 warm_q = s.best_q_S;
    const double warm_norm = s.best_norm;
    const Initializer warm_origin = s.best_origin;
    PolyDepthOptions check_options = options_;
    check_options.max_iterations = kCheckIterations;
    auto land_and_iterate = [&](const Vector3& q0) {
      bool touched = false;
      const Vector3 q_c =
          OutProjectRecording(pair, q0, Vector3::Zero(), margin, &touched, &s.record);
      if (touched && q_c.norm() < s.best_norm - options_.convergence_tol * size)
        s.Iterate(pair, check_options, size, q_c, Initializer::kSamplingSearch);
    };
    // A check's or turn's probe along u.
    auto probe = [&](const Vector3& u) {
      const Vector3 q0 = kCheckRadius * s.best_norm * u;
      // Most probes collide (the probe moved less than the depth): the
      // query's own intersecting triangle pair, or a neighbour, often still
      // intersects there and settles it in a few triangle tests (a probe's
      // collision test, box + triangle tests: knot1_camel 163 -> 61,
      // knot1_bunny 189 -> 114, bull_bunny 571 -> 211; cow_armadillo and
      // fandisk_elephant ~150 either way, their broad contact moves off it).
      CollisionWitness at_query = s.query_witness;
      if (!InCollision(pair, q0, &at_query)) land_and_iterate(q0);
    };
    if (check) {
      const Vector3 n = warm_q / warm_norm;
      const bool growing_fast =
          s.has_previous && warm_norm > (1.0 + kCheckFastGrowth) * s.previous_q_S.norm();
      const int per_query = growing_fast ? kCheckPerQueryFast : kCheckPerQuery;
      for (int probed = 0; s.check_next < kCheckDirections && probed < per_query &&
                           !s.BudgetSpent(kSearchShare);) {
        const Vector3 u = FibonacciDirection((s.check_next++ * kCheckStride) % kCheckDirections,
                                             kCheckDirections);
        if (u.dot(n) > kCheckOwnBasinCos || u.dot(n) < kFlipCos) continue;
        ++probed;
        probe(u);
      }
    } else if (turned) {
      probe(s.anchor_n_S);
      s.anchor_probe_depth = s.best_norm;
    } else {
      // 2e. Neighbour basins, every query between checks.
      localise_at_best();
      const Vector3 motion_S =
          s.has_previous ? Vector3(pair.X_SP.p_SP - s.previous_X_SP.p_SP) : Vector3::Zero();
      const int n = s.BasinProbeDirections(warm_q / warm_norm, motion_S);
      for (int i = 0; i < n && !s.BudgetSpent(kSearchShare); ++i) {
        const Vector3 q0 = kCheckRadius * warm_norm * s.basin_directions[i];
        ++result.basin_probes;
        if (s.BasinProbeCollides(pair, q0, s.basin_directions[i])) continue;
        land_and_iterate(q0);
        if (s.best_norm < warm_norm) break;
      }
      s.EndBasinProbes();
      s.previous_replaced_q_S = warm_q;  // for the next query if this one switches
    }
    if (s.best_q_S.dot(warm_q) <= kFlipCos * s.best_norm * warm_norm) {
      s.best_q_S = warm_q;
      s.best_norm = warm_norm;
      s.best_origin = warm_origin;
    }
    result.cross_checked = check || turned;
    result.basin_switched = s.best_norm < warm_norm && !result.cross_checked;
    if (check && s.check_next >= kCheckDirections) {
      // Anchor where the check started if the answer kept growing while it
      // ran (a drifting answer outruns a 16-query check: the next one starts
      // at once, not after a further 1.2x; on fandisk_elephant one answer
      // drifted 1.8 -> 2.8 mm over a shorter one at 2.0 mm before its check).
      s.check_next = -1;
      s.SetAnchor(s.best_norm < s.check_start_q_S.norm() ? s.best_q_S : s.check_start_q_S);
    }
  }

  // 3. Verify; fall back to a dense directional search if needed (not when
  // the budget is spent: then the answer is reported invalid instead).
  auto verified = [&] {
    return s.best_origin != Initializer::kNone &&
           (s.best_q_S == s.verified_q_S ||
            (s.best_q_S == s.surfaces_free_q_S ? !AnyComponentInside(pair, s.best_q_S)
                                               : !InCollision(pair, s.best_q_S)));
  };
  bool valid = verified();
  // 3a. Out of thin pockets: an answer that collides again a pocket's
  // thickness further along itself sits in a sliver of free space (the probe
  // against a feature that leans over the answer's direction); the next
  // frame's step-off along it lands in that feature and restarts cold. The
  // answer's own feature pairs flag it, a collision test confirms, and the
  // answer moves off all its feature pairs at once (along the direction that
  // clears them all) just far enough to be free beyond: a few pocket
  // thicknesses deeper, not a different answer.
  const double thickness = options_.pocket_thickness * size;
  if (valid && thickness > 0.0 && s.best_norm > 0.0) {
    localise_at_best();
    const Vector3 n = s.best_q_S / s.best_norm;
    const bool suspect =
        std::any_of(s.constraints.begin(), s.constraints.end(), [&](const ContactConstraint& c) {
          const double along = c.n_S.dot(n);
          return along < 0.0 && c.n_S.dot(s.best_q_S) - c.c + thickness * along < 0.0;
        });
    // The pocket's collision test, the escape's and the escaped answer's
    // localisation all lie within a few thicknesses of the answer. Where
    // neither the record nor the list answers for them (a budget-stopped
    // search leaves no record at its answer), one localisation here records
    // the leaf pairs they need, with room for the move, and they walk them
    // instead of descending each (cow_armadillo under a 900 us budget: the
    // finish's collision tests 3989 -> 845). Unbounded, the same work and
    // answers on haptic_work's 30 paths (the record or list always answers).
    const double escape_reach = contact_distance + kEscapeRecordRoom * thickness;
    if (suspect && !s.record.Covers(s.best_q_S, s.best_q_S, kEscapeRecordRoom * thickness) &&
        !(s.candidates.valid() &&
          s.candidates.Covers(pair, s.best_q_S, s.best_q_S, escape_reach))) {
      s.record.Invalidate();
      s.record.distance = std::max(s.record.distance, escape_reach + 2.0 * margin);
      CollectContactConstraints(pair, s.best_q_S, contact_distance, &s.constraints, &s.record);
    }
    if (suspect && InCollision(pair, s.best_q_S + thickness * n)) {
      ++result.pocket_escapes;
      // A free q that is free a thickness further along itself too; with
      // `move_back`, moved back in along itself to where the probe touches
      // (so the answer is again exactly where it leaves along itself).
      auto escape_to = [&](Vector3 q, bool move_back) {
        if (InCollision(pair, q) || InCollision(pair, q + thickness * q.normalized())) return false;
        bool touched = false;
        const Vector3 e = move_back ? OutProject(pair, q, Vector3::Zero(), margin, &touched) : q;
        // (A budget-stopped out-projection may not move: e == q, tested above.)
        if (touched && e != q && !InCollision(pair, e + thickness * e.normalized())) q = e;
        s.best_q_S = q;
        s.best_norm = q.norm();
        s.verified_q_S = q;
        s.constraints_q_S = Vector3::Constant(1e300);
        return true;
      };
      // Off the feature pairs that bound the pocket (those within a few
      // thicknesses of touching; the others are far at this scale) at once.
      s.pocket_constraints.clear();
      for (const ContactConstraint& c : s.constraints)
        if (c.n_S.dot(s.best_q_S) - c.c <= kPocketBoundSlack * thickness)
          s.pocket_constraints.push_back(c);
      double clearance = 0.0;
      const Vector3 d =
          s.ClearingDirection(s.pocket_constraints, options_.convergence_tol, &clearance);
      // The shortest move off them (the first) is not moved back: on
      // haptic_work's 30 paths all 189 escapes were, each gaining 2.0
      // thicknesses (0.02-0.06% of the depth) for an out-projection and a
      // collision test in a broad contact (1.5-2.6k tests).
      bool escaped = false;
      const double t0 = 2.0 * thickness / std::max(clearance, 1e-3);
      for (double t = t0; !escaped && clearance > 0.0 && t < 16.0 * contact_distance; t *= 4.0)
        escaped = escape_to(s.best_q_S + t * d, t > t0);
      // Wedged (no direction clears them all) or still inside: through the
      // pocket's far wall along the answer's own direction, and back in to
      // where the probe touches it from outside.
      for (double t = 2.0 * thickness; !escaped && t < 16.0 * contact_distance; t *= 4.0)
        escaped = escape_to(s.best_q_S + t * n, true);
    }
  }
  if (!valid && options_.num_sampling_directions > 0 && !s.stopped_early) {
    s.best_norm = 1e300;
    s.best_origin = Initializer::kNone;
    Vector3 best_contact = Vector3::Zero();
    double best_norm = 1e300;
    const int n = options_.num_sampling_directions;
    for (int i = 0; i < n; ++i) {
      const Vector3 u = FibonacciDirection(i, n);
      bool touched = false;
      const Vector3 q_c =
          OutProject(pair, SupportPlaneTranslation(pair, u), Vector3::Zero(), margin, &touched);
      if (touched && q_c.norm() < best_norm) best_norm = q_c.norm(), best_contact = q_c;
    }
    if (best_norm < 1e300)
      s.Iterate(pair, options_, size, best_contact, Initializer::kSamplingSearch);
    valid = verified();
  }

  result.valid = valid;
  result.converged = !s.stopped_early && !s.landings_cut;
  result.iterations = s.iterations;
  result.iterated_starts = s.iterated_starts;
  result.initializer = s.best_origin;
  if (s.best_origin != Initializer::kNone) {
    const Matrix3 R_WS = X_WS.linear();
    result.translation_W = R_WS * s.best_q_S;
    result.depth = s.best_norm;
    result.normal_W = s.best_norm > 0 ? Vector3(result.translation_W / s.best_norm)
                                      : Vector3::Zero();
    localise_at_best();
    result.num_contacts = static_cast<int>(s.constraints.size());
    GroupContactRegions(s.constraints, s.best_q_S, X_WS, 0.1 * size, &result);
  }
  s.has_previous_free = false;
  // The anchor follows the shallowest answer since the last cross-check
  // (or the first of a contact); see step 2.
  if (!valid) s.anchor_depth = 0.0;
  else if (s.anchor_depth <= 0.0 || s.best_norm < s.anchor_depth) s.SetAnchor(s.best_q_S);
  s.has_previous_replaced = valid && result.basin_switched;
  if (valid) {
    s.has_previous = true;
    s.previous_q_S = s.best_q_S;
    s.previous_n_S = s.best_q_S / std::max(s.best_norm, 1e-300);
    s.previous_X_SP = pair.X_SP;
    s.previous_constraints = s.constraints;
    // Deferred (PrepareNext): around the answer, which the query did not
    // know when it found its list short. A build under way that will cover
    // the answer goes on.
    if (s.build_wanted &&
        !s.next_candidates.BuildWillCover(pair, s.best_q_S, kListIterationRoom * contact_distance))
      s.next_candidates.BeginBuild(pair, s.best_q_S + s.wanted_lead, s.wanted_radius,
                                   s.NextGrain());
  } else {
    s.has_previous = false;
    s.previous_constraints.clear();
  }
  return finish();
}

}  // namespace pd
