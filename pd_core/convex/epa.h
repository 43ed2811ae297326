#pragma once
// EPA (expanding polytope algorithm) in double precision: the distance from
// an origin inside a convex set (given by its support function) to the set's
// boundary, and the direction of that nearest boundary point.
//
// Starts from the GJK simplex that enclosed the origin, completed to a
// tetrahedron or a triangular bipyramid (degenerate point, segment and
// triangle simplices are blown up with extra support points; a set that is
// flat on one side of the origin has depth 0). Each iteration takes the
// polytope face nearest the origin, adds the support point along its normal
// and re-triangulates the region visible from it, found by a depth-first
// search over face adjacency from that face (so the horizon is one loop). Lower bound: that face's distance;
// upper bound: the smallest support value seen along any face normal, which
// is always a valid answer (moving by it along that normal leaves the set).
// Converged when they are within tol_abs. Scratch memory is reused, so no
// allocation happens after the first queries of a pair.
#include <vector>

#include "pd_core/convex/gjk.h"

namespace pd {

struct EpaScratch {
  struct Face {
    int v[3];       // counter-clockwise seen from outside
    int adj[3];     // face across edge k (v[k] -> v[k+1])
    int adj_edge[3];  // that edge's index in the neighbour
    Vector3 n;      // unit outward normal (zero for a degenerate face)
    double d;       // n·vertex: distance of the plane from the origin
    bool alive;
  };
  std::vector<Vector3> vertices;
  std::vector<Face> faces;
  std::vector<std::pair<int, int>> horizon;  // (face, edge) on the silhouette
  std::vector<std::pair<int, int>> stack;    // depth-first search of visible faces
};

struct EpaResult {
  bool converged = false;
  double depth = 0.0;            // best upper bound (m): support value along normal_W
  double lower_bound = 0.0;      // nearest polytope face distance (m)
  Vector3 normal_W = Vector3::UnitZ();  // unit, direction of the exit
  int iterations = 0;
};

EpaResult Epa(const MinkowskiDifference& D, const GjkSimplex& simplex, double tol_abs,
              int max_iterations, EpaScratch* scratch);

}  // namespace pd
