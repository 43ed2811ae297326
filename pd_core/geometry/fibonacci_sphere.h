#pragma once
// Unit directions spread evenly over the sphere (Fibonacci lattice): the i-th
// of n, computed on demand so hot loops need no table.
#include <algorithm>
#include <cmath>

#include "pd_core/geometry/pose.h"

namespace pd {

inline Vector3 FibonacciDirection(int i, int n) {
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vector3(r * std::cos(golden * i), r * std::sin(golden * i), z);
}

}  // namespace pd
