#include "pd_core/polydepth/support_plane_starts.h"

#include <algorithm>
#include <cmath>

#include "pd_core/geometry/fibonacci_sphere.h"

namespace pd {

Vector3 SupportPlaneTranslation(const ModelPair& pair, const Vector3& u_S) {
  // Probe moved by lambda*u is beyond the plane u·x = h_S(u) when
  // min over probe of u·x >= h_S(u), i.e. lambda >= h_S(u) + h_P(-u).
  const double h_S = pair.S.SupportUpperBound(u_S);
  const Vector3 minus_u_P = -(pair.X_SP.R_SP.transpose() * u_S);
  const double h_P = pair.P.SupportUpperBound(minus_u_P) - u_S.dot(pair.X_SP.p_SP);
  // A small extra gap keeps the start strictly free under round-off.
  const double lambda = h_S + h_P + 1e-6 * pair.size();
  return std::max(lambda, 1e-6 * pair.size()) * u_S;
}

void ComputeSupportPlaneStarts(const ModelPair& pair, int num_directions,
                               std::vector<SupportPlaneStart>* out) {
  out->clear();
  for (int i = 0; i < num_directions; ++i) {
    const Vector3 q = SupportPlaneTranslation(pair, FibonacciDirection(i, num_directions));
    out->push_back({q, q.norm()});
  }
  std::sort(out->begin(), out->end(),
            [](const SupportPlaneStart& a, const SupportPlaneStart& b) { return a.length < b.length; });
}

}  // namespace pd
