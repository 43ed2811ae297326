#pragma once
// Point in closed mesh by ray parity, and the reference's containment test.
// Part of the slow independent reference (reference_pd.h).
#include "pd_core/reference/placed_pair.h"

namespace pd {
namespace reference {

// With P moved by t_W: is a piece of P inside closed S, or of S inside closed P?
// Only meaningful where the two surfaces do not touch.
bool Contained(const PairGeometry& g, const Vector3& t_W);

}  // namespace reference
}  // namespace pd
