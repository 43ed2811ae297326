#pragma once
// Triangle meshes standing in for primitives where a mesh algorithm
// (PolyDepth, the reference PD) needs one. The mesh circumscribes the
// primitive (every face plane at least the primitive's distance from its core,
// so the primitive lies inside the mesh) with a chord error, the largest gap
// between mesh and primitive, below `rel_chord_error` x the primitive's radius.
#include "pd_core/geometry/geometry.h"
#include "pd_core/mesh/mesh.h"

namespace pd {

// Capsule around the z segment [-half_length, half_length], vertices on the
// surface of radius `radius`: `segments` (>= 3) around the axis and `rings`
// (>= 1) latitude steps per hemisphere. Closed, counter-clockwise outside.
TriangleMesh MakeCapsuleMesh(double radius, double half_length, int segments, int rings);

// The mesh of any bounded geometry in its frame M: boxes exactly, mesh kinds
// as they are, sphere / capsule / cylinder circumscribed with a chord error
// of at most rel_chord_error * radius. Throws std::invalid_argument for the
// half-space.
TriangleMesh TessellateGeometry(const Geometry& geometry, double rel_chord_error = 3e-3);

// Largest distance (m) of the mesh's vertices outside the primitive `g`
// (sphere, capsule, cylinder; 0 for other kinds): for a circumscribed
// tessellation, how far it can be from the true shape.
double TessellationError(const Geometry& g, const TriangleMesh& mesh);

}  // namespace pd
