#pragma once
// Directional exit. Coordinates (x, y) in the plane normal to u, h along u.
// Triangle a of P moved by s*u touches triangle b of S exactly when their
// projections share a point q and s = h_b(q) - h_a(q); the set of such s is
// one closed interval whose ends are feature events: a vertex of one over the
// other triangle, or edge-edge crossings (endpoints on collinear edges, both
// heights of an edge parallel to u, when the projection degenerates).
// Part of the slow independent reference (reference_pd.h).
#include <algorithm>

#include "pd_core/reference/placed_pair.h"

namespace pd {
namespace reference {

struct Proj {
  double x, y, h;
};

// A contact normal in the (e1, e2, u) frame: unit and oriented along +u, or
// zero where undefined (features parallel to u).
struct Normal {
  double x = 0.0, y = 0.0, h = 0.0;
  // |u·n|: turns a gap length along u into its thickness; 1 if undefined.
  double cos() const { return h > 0.0 ? h : 1.0; }
};

// A touching interval with the contact normal at each end. Near-ties (within
// tol) keep the normal with the larger cosine, the conservative choice for
// slits.
struct Interval {
  double lo = kInf, hi = -kInf;
  Normal n_lo, n_hi;
  void Add(double s, const Normal& n, double tol) {
    if (s < lo - tol) {
      lo = s;
      n_lo = n;
    } else if (s <= lo + tol) {
      lo = std::min(lo, s);
      if (n.cos() > n_lo.cos()) n_lo = n;
    }
    if (s > hi + tol) {
      hi = s;
      n_hi = n;
    } else if (s >= hi - tol) {
      hi = std::max(hi, s);
      if (n.cos() > n_hi.cos()) n_hi = n;
    }
  }
};

// A projected triangle and what its pair tests need.
struct TriProj {
  Proj v[3];
  double ex[3], ey[3], eh[3];  // edge k = v[k+1] - v[k]
  double len1[3];              // L1 length of the projected edge k
  Normal n;                    // face normal; undefined when flat
  double orient = 1.0;         // sign of the projected area
  // Thinner than eps in projection, i.e. parallel to u: its face events are
  // replaced by events on its edges.
  bool flat = false;
};

TriProj MakeTriProj(const Proj& p0, const Proj& p1, const Proj& p2, double eps);

// The closed set of s with (a + s u) intersecting b; empty if lo > hi.
Interval PairInterval(const TriProj& a, const TriProj& b, double eps);

}  // namespace reference
}  // namespace pd
