#pragma once
// Primitive shapes as plain value types. Each primitive lives in its own frame
// M (placed in world by a pose X_WM); lengths are metres.
#include "pd_core/geometry/pose.h"

namespace pd {

struct HalfSpace {};                        // solid z <= 0 in M; boundary plane z = 0, outward normal +z
struct Sphere { double radius; };           // centred at the origin of M
struct Box { Vector3 half_extents; };       // centred, axis-aligned in M
struct Capsule { double radius; double half_length; };   // segment on z in [-half_length, half_length]
struct Cylinder { double radius; double half_length; };  // axis z, flat caps at z = ±half_length

// kConvexMesh: a mesh verified convex at load; kMesh: a general (possibly
// non-convex, possibly open) mesh, handled by PolyDepth.
enum class ShapeKind { kHalfSpace, kSphere, kBox, kCapsule, kCylinder, kConvexMesh, kMesh };
const char* ShapeKindName(ShapeKind kind);

}  // namespace pd
