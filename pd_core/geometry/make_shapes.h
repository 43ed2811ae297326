#pragma once
// Procedural closed manifold meshes for tests and demos. Every shape is built
// in its own frame M, lengths in metres, triangles counter-clockwise seen from
// outside (positive signed volume). Invalid sizes or counts throw
// std::invalid_argument.
#include "pd_core/mesh/mesh.h"

namespace pd {

// Axis-aligned box centred at the origin of M: 8 vertices, 12 triangles.
TriangleMesh MakeBox(const Vector3& half_extents);

// `mesh` with every vertex moved by p_M (m).
TriangleMesh TranslatedMesh(TriangleMesh mesh, const Vector3& p_M);

// One mesh of a's vertices and triangles followed by b's (indices shifted):
// a multi-part mesh where they share no vertex.
TriangleMesh JoinedMeshes(const TriangleMesh& a, const TriangleMesh& b);

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

// ---- Shapes for the haptic demo scenes (added with haptics/) ----

namespace pd {

// Open-top cup: a hollow cylinder with a floor, as one closed manifold (genus
// 0) with wall thickness. Axis z, centred at the origin, z in [-height/2,
// height/2]; outer radius `outer_radius`, inner radius outer_radius -
// wall_thickness, floor from the bottom up to -height/2 + floor_thickness; the
// opening faces +z. Needs wall_thickness < outer_radius and floor_thickness <
// height. 8 * segments - 4 triangles (segments >= 3); base and floor are
// zig-zag strips (no high-valence centre vertex).
TriangleMesh MakeCup(double outer_radius, double height, double wall_thickness,
                     double floor_thickness, int segments);

// Box of `half_extents` centred at the origin with a through-hole along z for
// peg-in-hole: round (radius `hole_half_width`, a regular polygon with
// `segments` sides whose vertices lie on the circle) or square (half side
// `hole_half_width`, axis-aligned). Genus 1. Needs hole_half_width <
// min(half_extents.x, half_extents.y), segments a multiple of 4 (>= 4; >= 8 for
// a round hole). 8 * segments triangles.
TriangleMesh MakeBlockWithHole(const Vector3& half_extents, double hole_half_width,
                               bool round_hole, int segments);

// L-shaped bar of square-ish cross-section: a non-convex tool. Lies in the xy
// plane, z in [-thickness/2, thickness/2]; the origin is the centre of the
// corner square (side `width`); one arm reaches x = arm_x, the other y =
// arm_y. Needs arm_x, arm_y > width / 2. 20 triangles.
TriangleMesh MakeLRod(double arm_x, double arm_y, double width, double thickness);

// Spoon-like stick with a bowl: a non-convex tool. The handle starts at x = 0
// and runs along +x; an elliptic bowl (bowl_length along x, bowl_width along
// y) ends at x ~= length. The slab has constant vertical thickness
// `thickness` (z in [-thickness/2, thickness/2] along the handle); inside the
// bowl outline both faces dip by up to bowl_depth, so the bowl opens toward +z.
struct SpoonDimensions {
  double length = 0.14;         // m, handle end to bowl tip
  double handle_width = 0.008;  // m
  double bowl_length = 0.045;   // m
  double bowl_width = 0.03;     // m, > handle_width
  double bowl_depth = 0.008;    // m
  double thickness = 0.003;     // m
  int segments_along = 8;       // bowl columns along x (>= 4)
  int segments_across = 4;      // columns across y (>= 2)
};
// 4 * (segments_along + 2) * segments_across + 4 * (segments_along + 2 +
// segments_across) triangles (216 with the defaults).
TriangleMesh MakeSpoon(const SpoonDimensions& dims);

}  // namespace pd
