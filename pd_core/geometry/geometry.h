#pragma once
// A collision geometry in its own frame M: a primitive (half-space, sphere,
// box, capsule, cylinder), a mesh verified convex, or a general mesh. Lengths
// in metres, points and directions in M (a pose X_WM places it in world W).
//
// Immutable after construction: share it as std::shared_ptr<const Geometry>
// between solvers and threads.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "pd_core/mesh/collision_model.h"
#include "pd_core/geometry/pose.h"
#include "pd_core/geometry/shape.h"

namespace pd {

// Thrown by Geometry::MakeConvexMesh for a mesh that is open, flat or not
// convex; the message names the mesh and how far it is from convex.
class NotConvexError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Geometry {
 public:
  static std::shared_ptr<const Geometry> MakeHalfSpace();
  // Sizes must be finite and > 0 (half_length >= 0 for the capsule, > 0 for
  // the cylinder); otherwise std::invalid_argument naming the field and value.
  static std::shared_ptr<const Geometry> MakeSphere(double radius);
  static std::shared_ptr<const Geometry> MakeBox(const Vector3& half_extents);
  static std::shared_ptr<const Geometry> MakeCapsule(double radius, double half_length);
  static std::shared_ptr<const Geometry> MakeCylinder(double radius, double half_length);
  // A mesh declared convex: verified closed, with positive volume, and every
  // vertex on the inner side of every face plane within 1e-6 of the mesh's
  // bounding radius (pd_core/mesh/convexity_check.h); throws NotConvexError whose
  // message gives the worst vertex-plane violation (m and relative to size)
  // otherwise. std::invalid_argument for a null model.
  static std::shared_ptr<const Geometry> MakeConvexMesh(std::shared_ptr<const CollisionModel> model);
  // A general mesh (any, closed or open), solved by PolyDepth.
  static std::shared_ptr<const Geometry> MakeMesh(std::shared_ptr<const CollisionModel> model);

  ShapeKind kind() const { return kind_; }
  bool convex() const { return kind_ != ShapeKind::kMesh; }
  bool bounded() const { return kind_ != ShapeKind::kHalfSpace; }

  // Bounding sphere in M (m). Half-space: infinite radius.
  const Vector3& center() const { return center_M_; }
  double radius() const { return radius_; }
  // Axis-aligned box of the geometry in M (half-space: -inf..inf in x, y and
  // -inf..0 in z).
  Vector3 aabb_min() const { return aabb_min_M_; }
  Vector3 aabb_max() const { return aabb_max_M_; }

  // Support point: argmax over x in the shape of u_M·x (u_M need not be unit;
  // a zero u_M gives some point of the shape). For a general mesh: over its
  // convex hull. Not defined for the half-space (throws std::logic_error).
  Vector3 Support(const Vector3& u_M) const;

  // Shapes that are a core swept by a ball: sphere (core = its centre) and
  // capsule (core = its segment) have margin() = radius; every other kind has
  // margin 0 and core = the shape. Support(u) = CoreSupport(u) + margin()*û.
  double margin() const { return margin_; }
  Vector3 CoreSupport(const Vector3& u_M) const;

  // Point containment (closed solid, boundary counts as inside) in M. Open
  // meshes: false.
  bool Contains(const Vector3& p_M) const;

  // Surface points used as pressure points for contact torque: mesh vertices;
  // box: the 26 points of the {-1,0,1}^3 lattice of half extents except the
  // centre (corners, edge midpoints, face centres); sphere: 3 rings x 12 +
  // poles; capsule: 12 points on each of the rings at z = ±half_length + poles
  // + 12 on each hemisphere at 45°; cylinder: 12 on each rim + cap centres + 12
  // on the middle ring. Empty for the half-space.
  const std::vector<Vector3>& surface_points() const { return surface_points_M_; }

  // The collision model for mesh kinds (nullptr for primitives).
  const std::shared_ptr<const CollisionModel>& model() const { return model_; }

  // Primitive parameters; throw std::logic_error for another kind.
  const Sphere& sphere() const;
  const Box& box() const;
  const Capsule& capsule() const;
  const Cylinder& cylinder() const;

  // Description for messages, e.g. "sphere(radius=0.05)" or "mesh 'cup.off'".
  std::string Describe() const;

 private:
  Geometry() = default;
  void FinishPrimitive();
  void RequireKind(ShapeKind kind, const char* accessor) const;  // logic_error otherwise
  ShapeKind kind_ = ShapeKind::kHalfSpace;
  Sphere sphere_{0.0};
  Box box_{Vector3::Zero()};
  Capsule capsule_{0.0, 0.0};
  Cylinder cylinder_{0.0, 0.0};
  double margin_ = 0.0;
  std::shared_ptr<const CollisionModel> model_;
  std::vector<Vector3> hull_points_M_;  // mesh kinds: hull candidate vertices
  // Convex mesh: face planes n·x <= d (unit n) for containment.
  std::vector<Vector3> face_normals_M_;
  std::vector<double> face_offsets_;
  double contains_tol_ = 0.0;  // m, relative to the radius
  Vector3 center_M_ = Vector3::Zero();
  double radius_ = 0.0;
  Vector3 aabb_min_M_ = Vector3::Zero();
  Vector3 aabb_max_M_ = Vector3::Zero();
  std::vector<Vector3> surface_points_M_;
};

}  // namespace pd
