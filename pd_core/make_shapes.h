#pragma once
// Procedural closed manifold meshes for tests and demos. Every shape is built
// in its own frame M, lengths in metres, triangles counter-clockwise seen from
// outside (positive signed volume). Invalid sizes or counts throw
// std::invalid_argument.
#include "pd_core/mesh.h"

namespace pd {

// Axis-aligned box centred at the origin of M: 8 vertices, 12 triangles.
TriangleMesh MakeBox(const Vector3& half_extents);

// Sphere of `radius` centred at the origin: an icosahedron split
// `subdivisions` times (20 * 4^subdivisions triangles, 0..8), vertices on the
// sphere, so the mesh lies inside the true sphere.
TriangleMesh MakeIcosphere(double radius, int subdivisions);

// Cylinder with axis z, centred at the origin, z in [-length/2, length/2];
// `segments` >= 3 around the axis (4 * segments triangles).
TriangleMesh MakeCylinder(double radius, double length, int segments);

// Torus around the z axis, centred at the origin: tube centre circle of radius
// `major_radius` in the xy plane, tube radius `minor_radius` < major_radius.
TriangleMesh MakeTorus(double major_radius, double minor_radius, int major_segments,
                       int minor_segments);

// Closed tube of radius `tube_radius` along a (p, q) torus knot (p, q coprime,
// >= 1) that winds p times around the z axis and q times through the hole of
// a torus with major radius `scale` and minor radius scale / 2, centred at the
// origin. 2 * segments * tube_segments triangles (3072 with the defaults): a
// procedural stand-in for the knot of the PolyDepth paper. Throws if the tube
// would intersect itself.
TriangleMesh MakeTorusKnot(int p, int q, double tube_radius, double scale,
                           int segments = 256, int tube_segments = 6);

// Box of `outer_half_extents` centred at the origin with a rectangular slot of
// `slot_width` (along y, centred) and `slot_depth` (down from the top face
// z = +hz) cut through its whole length along x: a U-shaped cross-section in
// the yz plane, extruded along x. A peg in the slot is blocked sideways (y)
// and downward (-z); it leaves upward (+z) or along the slot (x). Needs
// slot_width < 2 hy and slot_depth < 2 hz. 28 triangles.
TriangleMesh MakeUSlot(const Vector3& outer_half_extents, double slot_width, double slot_depth);

// Flat box, x in [-half_x, half_x], y in [-half_y, half_y], z in
// [-half_thickness, half_thickness]: a thin obstacle a fast probe can tunnel
// through.
TriangleMesh MakeThinPlate(double half_x, double half_y, double half_thickness);

}  // namespace pd
