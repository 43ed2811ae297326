// Cross-checks of a coherent answer (Solve's steps 2b-2e): a followed local
// optimum drifts from the PD as the probe moves, so each coherent query
// probes free space inside its answer for shallower basins, a few
// directions per query: a check over many directions once the answer has
// grown, a probe back along the anchor's direction once it has turned, and
// between them probes along its own contact normals and the motion.
#include <algorithm>
#include <array>
#include <cmath>

#include "pd_core/geometry/fibonacci_sphere.h"
#include "pd_core/polydepth/depth_lower_bound.h"
#include "pd_core/polydepth/out_projection.h"
#include "pd_core/polydepth/polydepth_search.h"

namespace pd {
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
// degrees off (most 10-40), carrying 0.87 of the 0.93% mean error. A
// probe's landing is free 2.5% of the time and then almost always shorter
// (80 of 82). Mean error 0.93 ->
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
// (kBasinNormalProbes, kBasinProbes: polydepth_search.h.)
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

}  // namespace

int PolyDepthSolver::Impl::BasinProbeDirections(const Vector3& n, const Vector3& v_S) {
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
    basin_directions[count++] =
        std::cos(kBasinMotionAngle) * n + std::sin(kBasinMotionAngle) * across.normalized();
  }
  return count;
}

bool PolyDepthSolver::Impl::BasinProbeCollides(const ModelPair& pair, const Vector3& q0,
                                               const Vector3& u) {
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

void PolyDepthSolver::Impl::EndBasinProbes() {
  std::swap(basin_witnesses, next_basin_witnesses);
  num_basin_witnesses = num_next_basin_witnesses;
  num_next_basin_witnesses = 0;
}
void PolyDepthSolver::Impl::CheckCoherentAnswer(const ModelPair& pair, const PolyDepthOptions& opt,
                                                PenetrationResult* result) {
  const double size = pair.size();
  const double margin = opt.separation_margin * size;
  const double contact_distance = opt.contact_tol * size;
  // 2b. Cross-check of a coherent answer that has grown much deeper than
  // where it was last anchored (a followed local optimum can drift far from
  // the PD): probe free space around the query inside the coherent answer's
  // length, a few directions per query. A probe that is free out-projects
  // toward the query; landing shorter, it is iterated and becomes the answer
  // the next queries follow. Any shorter answer is reachable this way from
  // the direction it lies in, so the check needs no far-away starts (a burst
  // of cold starts here cost 10-30 ms).
  // (A bounded query out of budget leaves both to the next query.)
  const bool budget_left = !OutOfBudget();
  const bool check =
      budget_left &&
      (check_next >= 0 ||
       (anchor_depth > 0.0 && best_norm > kReanchorGrowth * anchor_depth + kReanchorFloor * size));
  // 2c. Between checks, a coherent answer that has turned away from the
  // anchor's direction while growing deeper gets one probe back along that
  // direction: the basin it follows is drifting, and a shallower one usually
  // opens back toward where the answer was (fandisk_elephant: the reference
  // lay 7-15 degrees from the anchor's direction while the followed answer
  // turned 14-48 degrees away and grew 1.22 -> 2.02 mm before the check's
  // 1.2x trigger; mean error on the bench's poses 6.1% -> 0.5%).
  const bool turned = budget_left && !check && anchor_depth > 0.0 &&
                      best_norm > kAnchorProbeGrowth * std::max(anchor_depth, anchor_probe_depth) &&
                      best_q_S.dot(anchor_n_S) < kAnchorProbeCos * best_norm;
  // 2e (below): otherwise, probes along the answer's own contact normals.
  // 2d. Before 2b or 2c: the answer's own contact may prove it within
  // kProvedSlack of the PD (depth_lower_bound.h).
  auto answer_proved = [&] {
    LocaliseAtBest(pair, contact_distance);
    return ProvesDepthAtLeast(pair, constraints, best_norm / (1.0 + kProvedSlack));
  };
  if ((check || turned) && answer_proved()) {
    // Every probe would collide: none run; a running check ends here and the
    // anchor moves to the answer.
    if (check) {
      check_next = -1;
      SetAnchor(best_q_S);
    } else {
      anchor_probe_depth = best_norm;
    }
  } else if (budget_left) {
    // 2b, 2c or 2e: probes at kCheckRadius of the answer's length. A free
    // probe is out-projected toward the query and iterated if it lands
    // shorter; the following queries' coherent updates go on from there.
    if (check && check_next < 0) {
      check_next = 0;
      check_start_q_S = best_q_S;
    }
    const Vector3 warm_q = best_q_S;
    const double warm_norm = best_norm;
    const Initializer warm_origin = best_origin;
    PolyDepthOptions check_options = opt;
    check_options.max_iterations = kCheckIterations;
    auto land_and_iterate = [&](const Vector3& q0) {
      bool touched = false;
      const Vector3 q_c = OutProjectRecording(pair, q0, Vector3::Zero(), margin, &touched, &record);
      if (touched && q_c.norm() < best_norm - opt.convergence_tol * size)
        Iterate(pair, check_options, size, q_c, Initializer::kSamplingSearch);
    };
    // A check's or turn's probe along u.
    auto probe = [&](const Vector3& u) {
      const Vector3 q0 = kCheckRadius * best_norm * u;
      // Most probes collide (the probe moved less than the depth): the
      // query's own intersecting triangle pair, or a neighbour, often still
      // intersects there and settles it in a few triangle tests (a probe's
      // collision test, box + triangle tests: knot1_camel 163 -> 61,
      // knot1_bunny 189 -> 114, bull_bunny 571 -> 211; cow_armadillo and
      // fandisk_elephant ~150 either way, their broad contact moves off it).
      CollisionWitness at_query = query_witness;
      if (!InCollision(pair, q0, &at_query)) land_and_iterate(q0);
    };
    if (check) {
      const Vector3 n = warm_q / warm_norm;
      const bool growing_fast =
          has_previous && warm_norm > (1.0 + kCheckFastGrowth) * previous_q_S.norm();
      const int per_query = growing_fast ? kCheckPerQueryFast : kCheckPerQuery;
      for (int probed = 0;
           check_next < kCheckDirections && probed < per_query && !BudgetSpent(kSearchShare);) {
        const Vector3 u =
            FibonacciDirection((check_next++ * kCheckStride) % kCheckDirections, kCheckDirections);
        if (u.dot(n) > kCheckOwnBasinCos || u.dot(n) < kFlipCos) continue;
        ++probed;
        probe(u);
      }
    } else if (turned) {
      probe(anchor_n_S);
      anchor_probe_depth = best_norm;
    } else {
      // 2e. Neighbour basins, every query between checks.
      LocaliseAtBest(pair, contact_distance);
      const Vector3 motion_S =
          has_previous ? Vector3(pair.X_SP.p_SP - previous_X_SP.p_SP) : Vector3::Zero();
      const int n = BasinProbeDirections(warm_q / warm_norm, motion_S);
      for (int i = 0; i < n && !BudgetSpent(kSearchShare); ++i) {
        const Vector3 q0 = kCheckRadius * warm_norm * basin_directions[i];
        ++result->basin_probes;
        if (BasinProbeCollides(pair, q0, basin_directions[i])) continue;
        land_and_iterate(q0);
        if (best_norm < warm_norm) break;
      }
      EndBasinProbes();
      previous_replaced_q_S = warm_q;  // for the next query if this one switches
    }
    if (best_q_S.dot(warm_q) <= kFlipCos * best_norm * warm_norm) {
      best_q_S = warm_q;
      best_norm = warm_norm;
      best_origin = warm_origin;
    }
    result->cross_checked = check || turned;
    result->basin_switched = best_norm < warm_norm && !result->cross_checked;
    if (check && check_next >= kCheckDirections) {
      // Anchor where the check started if the answer kept growing while it
      // ran (a drifting answer outruns a 16-query check: the next one starts
      // at once, not after a further 1.2x; on fandisk_elephant one answer
      // drifted 1.8 -> 2.8 mm over a shorter one at 2.0 mm before its check).
      check_next = -1;
      SetAnchor(best_norm < check_start_q_S.norm() ? best_q_S : check_start_q_S);
    }
  }
}

}  // namespace pd
