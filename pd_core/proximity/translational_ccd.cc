#include "pd_core/proximity/translational_ccd.h"

#include <algorithm>
#include <utility>

#include "pd_core/proximity/box_overlap.h"
#include "pd_core/proximity/bvh_pair_descent.h"
#include "pd_core/proximity/candidate_pairs.h"
#include "pd_core/proximity/descent_front.h"
#include "pd_core/proximity/placed_probe_triangles.h"
#include "pd_core/proximity/triangle_geometry.h"

namespace pd {
namespace {

// A list walk's part whose prefix holds more than this fraction of the
// covered part's walks the covered part at once (below).
constexpr double kWalkCoveredAtOnce = 0.5;
// A list walk asks the caller's stop once per this many entries (a time
// budget reads the clock each time it is asked).
constexpr int kEntriesPerStopAsk = 16;

// Earliest contact of one probe triangle swept along sweep_S with one scene
// triangle, over the features each owns. Lowers *s_best on a hit.
void TriangleFirstContact(const ModelPair& pair, PlacedProbeTriangles& placed, int tp, int ts,
                          const Vector3& sweep_S, double* s_best, bool* hit) {
  const PlacedProbeTriangles::Triangle& probe = placed(tp);
  const Vector3* p = probe.p;
  Vector3 s[3];
  pair.SceneTriangle(ts, s);
  // Every event puts a point of each triangle on the other's plane. Along
  // the sweep, each triangle's vertices move off the other's plane at one
  // common rate, so the triangles can only touch while the nearest vertex
  // has not passed the plane and the farthest has reached it: an empty
  // s-interval in [0, *s_best] skips the pair (most pairs of a leaf pair
  // near a contact). Degenerate triangles (zero normal) are never skipped;
  // `slack` keeps round-off from skipping a pair the exact tests would keep.
  const double slack = 1e-9 * pair.size();
  const Vector3& n_S = pair.S.face_normals()[ts];
  if (TriangleStaysOffPlane(n_S, s[0], p, n_S.dot(sweep_S) * *s_best, slack)) return;
  const Vector3& n_P = probe.n;
  if (TriangleStaysOffPlane(n_P, p[0], s, -n_P.dot(sweep_S) * *s_best, slack)) return;
  const uint8_t op = pair.P.owned_features()[tp], os = pair.S.owned_features()[ts];
  auto consider = [&](double t) {
    if (t >= 0 && t <= *s_best) {
      *s_best = t;
      *hit = true;
    }
  };
  const Vector3 back_S = -sweep_S;
  for (int k = 0; k < 3; ++k) {
    if (op & (1u << k)) consider(RayTriangle(p[k], sweep_S, s[0], s[1], s[2], *s_best));
    if (os & (1u << k)) consider(RayTriangle(s[k], back_S, p[0], p[1], p[2], *s_best));
  }
  for (int i = 0; i < 3; ++i) {
    if (!(op & (8u << i))) continue;
    for (int j = 0; j < 3; ++j) {
      if (!(os & (8u << j))) continue;
      consider(EdgeEdgeTranslationalContact(p[i], p[(i + 1) % 3], s[j], s[(j + 1) % 3], sweep_S,
                                            *s_best));
    }
  }
}

}  // namespace

double FirstContactAlongTranslation(const ModelPair& pair, const Vector3& offset_S,
                                    const Vector3& sweep_S, double s_stop,
                                    LeafPairRecord* record, bool* record_complete, bool* stopped) {
  WorkScope scope(pair.counters, QueryKind::kOutProjection);
  if (stopped) *stopped = false;
  const Bvh& bvh_P = pair.P.bvh();
  const Bvh& bvh_S = pair.S.bvh();
  if (record_complete) *record_complete = false;
  if (record) record->pairs.clear();
  if (bvh_P.empty() || bvh_S.empty()) return -1.0;
  double s_best = 1.0;
  bool hit = false;
  double lo, hi;
  PlacedProbeTriangles placed(pair, offset_S);
  // False once a contact before s_stop is known (the caller's early stop).
  auto leaf_contacts = [&](int ip, int is) {
    return ForEachTrianglePair(bvh_P, bvh_S, ip, is, [&](int tp, int ts) {
      if (pair.counters) ++pair.counters->triangle_tests;
      TriangleFirstContact(pair, placed, tp, ts, sweep_S, &s_best, &hit);
      return !(hit && s_best < s_stop);
    });
  };
  const CandidatePairs* list = pair.candidates;
  const SweepInS sweep(sweep_S);
  SweptProbeBoxMemo probe_box(pair.X_SP, offset_S, sweep, pair.probe_boxes, bvh_P.nodes().data());
  const double covered = list ? list->CoveredFraction(pair, offset_S, sweep_S, 0.0) : -1.0;
  // The part of the sweep the list has shown contact-free: the descent
  // below looks past it only (the pairs in contact at the start, which the
  // sweep leaves, drop out once their boxes part before it).
  double s_min = 0.0;
  double grow = 0.0;  // the boxes' growth while recording (below)
  // The node test of every walk and descent here: the swept boxes (grown by
  // `grow`) may meet in [s_min, s_best], from `*key` on.
  auto may_meet = [&](const BvhNode& a, const BvhNode& b, double* key) {
    if (!SweptBoxContactInterval(probe_box(a), b, sweep, s_best, &lo, &hi, grow, s_min))
      return false;
    *key = lo;
    return true;
  };
  auto before_best = [&](double s_lo) { return s_lo <= s_best; };
  auto stop = [&] { return pair.stop_ccd != nullptr && (*pair.stop_ccd)(); };
  if (covered > 0.0) {
    // Every pair that can touch on [0, s] is in the list's prefix for the
    // largest displacement over that part of the sweep; a first contact
    // found there is exact. First contacts are usually close to the start
    // (a start just off the contact space), so look at short parts first,
    // doubling up to the covered fraction; past it, the full descent.
    const auto& nodes_P = bvh_P.nodes();
    const auto& nodes_S = bvh_S.nodes();
    const double start_displacement = list->Displacement(pair, offset_S);
    const double sweep_len = sweep_S.norm();
    double s_part = std::min(covered, 0.05 * list->radius() / std::max(sweep_len, 1e-300));
    // The probe's motion since the list's build at the sweep's start; along
    // the sweep it adds s * sweep_S (same rotation bound).
    Vector3 shift_from;
    double rot = 0.0;
    list->MotionSinceBuild(pair, offset_S, &shift_from, &rot);
    const int n_covered = list->NearCount(0.0, start_displacement + covered * sweep_len);
    for (double s_free = 0.0;; s_free = s_part, s_part = std::min(covered, 4.0 * s_part)) {
      // The caller's stop, between parts: contact-free up to the last part.
      if (s_free > 0.0 && stop()) {
        if (stopped) *stopped = true;
        return s_free;
      }
      // Where this part's prefix is most of the covered one already (a dense
      // list the probe has moved across since its build), shorter parts
      // would walk nearly the same entries again: walk the covered part once
      // (haptic_work: total work -1.5%, cow_armadillo -3.5%, p99 -3%; at
      // 0.8 half the gain, at 0 and 0.3 the same total with more p99 up).
      int n = list->NearCount(0.0, start_displacement + s_part * sweep_len);
      if (s_part < covered && n > kWalkCoveredAtOnce * n_covered) {
        s_part = covered;
        n = n_covered;
      }
      s_best = s_part;
      // The walk of [0, s_free] was complete and met nothing: this part
      // looks past it only (pairs touching at the start drop out once they
      // part).
      s_min = s_free;
      const Vector3 shift_to = shift_from + s_part * sweep_S;
      int64_t tested = 0;
      for (int k = 0; k < n; ++k) {
        // The caller's stop, within a part too (a dense list's covered part
        // is up to a few thousand entries: a bounded query ran 1.6k tests
        // past its budget in one): contact-free up to the last part.
        if (k % kEntriesPerStopAsk == kEntriesPerStopAsk - 1) {
          if (pair.counters) pair.counters->box_tests += std::exchange(tested, 0);
          if (stop()) {
            if (stopped) *stopped = true;
            return s_free;
          }
        }
        const CandidatePairs::Entry& e = list->entries()[k];
        // Along the entry's separating axis first (a dot product): the
        // swept probe leaf stays at least this far from the scene leaf.
        if (e.StaysApart(shift_from, shift_to, rot, 0.0)) continue;
        if (nodes_P[e.ip].is_leaf() && nodes_S[e.is].is_leaf()) {
          ++tested;
          double key;
          if (may_meet(nodes_P[e.ip], nodes_S[e.is], &key) && !leaf_contacts(e.ip, e.is)) break;
        } else if (!DescendBvhPair(bvh_P, bvh_S, may_meet, before_best, leaf_contacts,
                                   pair.counters, e.ip, e.is)) {
          break;
        }
      }
      if (pair.counters) pair.counters->box_tests += tested;
      if (hit) return s_best;
      if (s_part >= covered) break;
    }
    if (covered >= 1.0) return -1.0;
    s_best = 1.0;
    s_min = covered;
  }
  // Earliest possible contact first over all pending node pairs: the first
  // contact is found expanding only pairs that may touch before it, and the
  // descent ends once the earliest pending pair is later than it.
  // The caller's stop: contact-free up to the lowest pending key.
  double free_until = 2.0;
  auto result = [&] {
    if (free_until <= 1.0 && !(hit && s_best <= free_until)) {
      if (stopped) *stopped = true;
      return std::max(free_until, s_min);
    }
    return hit ? s_best : -1.0;
  };
  // A sweep from where the last descent ended (a search's next iteration)
  // starts at that descent's cut (descent_front.h), and leaves its own.
  DescentFront* front = FrontNear(pair, offset_S);
  auto descend = [&](auto&& on_leaf) {
    if (front != nullptr) {
      DescendBvhPairFromFront<DescentOrder::kBestFirst>(bvh_P, bvh_S, may_meet, before_best,
                                                        on_leaf, pair.counters, front,
                                                        kMaxFrontPairs, stop, &free_until);
      front->q_S = offset_S + (hit ? s_best : 1.0) * sweep_S;
    } else {
      DescendBvhPair<DescentOrder::kBestFirst>(bvh_P, bvh_S, may_meet, before_best, on_leaf,
                                               pair.counters, 0, 0, stop, &free_until);
    }
  };
  if (record == nullptr || s_stop >= 0.0) {
    descend(leaf_contacts);
    return result();
  }
  // Recording: boxes grown by the record's distance (with a relative slack
  // against round-off), keyed by when they come that near. A leaf pair within
  // the distance at some s before the first contact has every ancestor pair
  // keyed at or before s, so it is reached and recorded; the same
  // first contact is found (its triangle pairs are among those reached).
  grow = record->distance * (1.0 + 1e-9) + 1e-12 * pair.size();
  descend([&](int ip, int is) {
    record->pairs.push_back({ip, is});
    return leaf_contacts(ip, is);
  });
  if (record_complete) *record_complete = free_until > 1.0;
  return result();
}

}  // namespace pd
