#pragma once
// Mesh checks shared by the pd_core and haptics test suites.
#include <map>
#include <utility>

#include "pd_core/mesh/mesh.h"

namespace pd::test {

// Volume enclosed by a closed mesh (m^3); positive when triangles are CCW outside.
inline double SignedVolume(const TriangleMesh& mesh) {
  double six_v = 0.0;
  for (const auto& t : mesh.triangles)
    six_v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  return six_v / 6.0;
}

// Each directed edge used once and its reverse used once: the two faces of
// every edge agree on orientation (which the undirected topology cannot see).
inline bool ConsistentlyOriented(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    auto reverse = directed.find({edge.second, edge.first});
    if (reverse == directed.end() || reverse->second != 1) return false;
  }
  return true;
}

}  // namespace pd::test
