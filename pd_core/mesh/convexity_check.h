#pragma once
// Is a mesh convex? A closed, consistently outward-oriented mesh with positive
// volume is convex iff no vertex lies outside any face plane. Only the
// model's hull-candidate vertices need checking (a violation by any vertex
// implies one at least as large by a hull vertex).
#include <string>

#include "pd_core/mesh/collision_model.h"

namespace pd {

struct ConvexityReport {
  bool convex = false;
  double volume = 0.0;           // signed volume (m^3), > 0 when outward-oriented
  double max_violation = 0.0;    // worst vertex distance outside a face plane (m)
  double relative_violation = 0.0;  // max_violation / bounding radius
  int worst_vertex = -1, worst_face = -1;
  std::string message;           // why not convex (empty when convex)
};

// rel_tol: allowed violation as a fraction of the model's bounding radius
// (covers coordinates written with ~7 significant digits).
ConvexityReport CheckConvexity(const CollisionModel& model, double rel_tol = 1e-6);

}  // namespace pd
