#pragma once
// Maximally clear configurations from the models' precomputed support data:
// for a direction u, the shortest translation along u at which a plane
// normal to u separates the two models. Such a configuration is certainly
// collision-free and, for the best directions, close to the contact space,
// which makes it a good start for out-projection.
#include <vector>

#include "pd_core/proximity/model_pair.h"

namespace pd {

struct SupportPlaneStart {
  Vector3 q_S;    // probe translation in S (m), collision-free
  double length;  // |q_S|
};

// Separating translation along unit u_S (m, in S).
Vector3 SupportPlaneTranslation(const ModelPair& pair, const Vector3& u_S);

// Separating translations along num_directions Fibonacci directions
// (FibonacciDirection), shortest first.
void ComputeSupportPlaneStarts(const ModelPair& pair, int num_directions,
                               std::vector<SupportPlaneStart>* out);

}  // namespace pd
