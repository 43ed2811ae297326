#include "pd_core/geometry/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "pd_core/mesh/convexity_check.h"
#include "pd_core/proximity/point_in_mesh.h"

namespace pd {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Throws std::invalid_argument unless `value` is finite and > 0 (or >= 0).
void RequirePositive(const char* shape, const char* field, double value, bool allow_zero = false) {
  if (std::isfinite(value) && (value > 0.0 || (allow_zero && value == 0.0))) return;
  std::ostringstream msg;
  msg << shape << ": " << field << " must be finite and " << (allow_zero ? ">= 0" : "> 0")
      << ", got " << value;
  throw std::invalid_argument(msg.str());
}

// Points on a ring of radius r at height z, `n` evenly spaced.
void AddRing(double r, double z, int n, std::vector<Vector3>* out) {
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    out->emplace_back(r * std::cos(a), r * std::sin(a), z);
  }
}

double Sign(double x) { return x < 0.0 ? -1.0 : 1.0; }

}  // namespace

std::shared_ptr<const Geometry> Geometry::MakeHalfSpace() {
  auto g = std::shared_ptr<Geometry>(new Geometry());
  g->kind_ = ShapeKind::kHalfSpace;
  g->radius_ = kInf;
  g->aabb_min_M_ = Vector3(-kInf, -kInf, -kInf);
  g->aabb_max_M_ = Vector3(kInf, kInf, 0.0);
  return g;
}

std::shared_ptr<const Geometry> Geometry::MakeSphere(double radius) {
  RequirePositive("sphere", "radius", radius);
  auto g = std::shared_ptr<Geometry>(new Geometry());
  g->kind_ = ShapeKind::kSphere;
  g->sphere_ = Sphere{radius};
  g->margin_ = radius;
  g->radius_ = radius;
  g->aabb_max_M_ = Vector3::Constant(radius);
  const double c = radius * std::sqrt(0.5);
  AddRing(radius, 0.0, 12, &g->surface_points_M_);
  AddRing(c, c, 12, &g->surface_points_M_);
  AddRing(c, -c, 12, &g->surface_points_M_);
  g->surface_points_M_.emplace_back(0, 0, radius);
  g->surface_points_M_.emplace_back(0, 0, -radius);
  g->FinishPrimitive();
  return g;
}

std::shared_ptr<const Geometry> Geometry::MakeBox(const Vector3& half_extents) {
  static const char* kFields[3] = {"half_extents.x", "half_extents.y", "half_extents.z"};
  for (int k = 0; k < 3; ++k) RequirePositive("box", kFields[k], half_extents[k]);
  auto g = std::shared_ptr<Geometry>(new Geometry());
  g->kind_ = ShapeKind::kBox;
  g->box_ = Box{half_extents};
  g->radius_ = half_extents.norm();
  g->aabb_max_M_ = half_extents;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (i || j || k)
          g->surface_points_M_.push_back(Vector3(i, j, k).cwiseProduct(half_extents));
  g->FinishPrimitive();
  return g;
}

std::shared_ptr<const Geometry> Geometry::MakeCapsule(double radius, double half_length) {
  RequirePositive("capsule", "radius", radius);
  RequirePositive("capsule", "half_length", half_length, /*allow_zero=*/true);
  auto g = std::shared_ptr<Geometry>(new Geometry());
  g->kind_ = ShapeKind::kCapsule;
  g->capsule_ = Capsule{radius, half_length};
  g->margin_ = radius;
  g->radius_ = radius + half_length;
  g->aabb_max_M_ = Vector3(radius, radius, radius + half_length);
  const double c = radius * std::sqrt(0.5);
  AddRing(radius, half_length, 12, &g->surface_points_M_);
  AddRing(radius, -half_length, 12, &g->surface_points_M_);
  AddRing(c, half_length + c, 12, &g->surface_points_M_);
  AddRing(c, -half_length - c, 12, &g->surface_points_M_);
  g->surface_points_M_.emplace_back(0, 0, half_length + radius);
  g->surface_points_M_.emplace_back(0, 0, -half_length - radius);
  g->FinishPrimitive();
  return g;
}

std::shared_ptr<const Geometry> Geometry::MakeCylinder(double radius, double half_length) {
  RequirePositive("cylinder", "radius", radius);
  RequirePositive("cylinder", "half_length", half_length);
  auto g = std::shared_ptr<Geometry>(new Geometry());
  g->kind_ = ShapeKind::kCylinder;
  g->cylinder_ = Cylinder{radius, half_length};
  g->radius_ = std::hypot(radius, half_length);
  g->aabb_max_M_ = Vector3(radius, radius, half_length);
  AddRing(radius, half_length, 12, &g->surface_points_M_);
  AddRing(radius, -half_length, 12, &g->surface_points_M_);
  AddRing(radius, 0.0, 12, &g->surface_points_M_);
  g->surface_points_M_.emplace_back(0, 0, half_length);
  g->surface_points_M_.emplace_back(0, 0, -half_length);
  g->FinishPrimitive();
  return g;
}

void Geometry::FinishPrimitive() {
  center_M_ = Vector3::Zero();
  aabb_min_M_ = -aabb_max_M_;
}

std::shared_ptr<const Geometry> Geometry::MakeMesh(std::shared_ptr<const CollisionModel> model) {
  if (!model) throw std::invalid_argument("Geometry::MakeMesh: null collision model");
  if (model->mesh().num_vertices() == 0)
    throw std::invalid_argument("Geometry::MakeMesh: mesh '" + model->mesh().name +
                                "' has no vertices");
  auto g = std::shared_ptr<Geometry>(new Geometry());
  g->kind_ = ShapeKind::kMesh;
  g->model_ = model;
  g->center_M_ = model->center();
  g->radius_ = model->radius();
  const MeshBounds b = ComputeBounds(model->mesh());
  g->aabb_min_M_ = b.min;
  g->aabb_max_M_ = b.max;
  // Exact support over the hull needs every vertex (the model's hull
  // candidates come from sampled directions and may miss some).
  g->hull_points_M_ = model->mesh().vertices;
  g->surface_points_M_ = model->mesh().vertices;
  return g;
}

std::shared_ptr<const Geometry> Geometry::MakeConvexMesh(
    std::shared_ptr<const CollisionModel> model) {
  if (!model) throw std::invalid_argument("Geometry::MakeConvexMesh: null collision model");
  const ConvexityReport report = CheckConvexity(*model);
  if (!report.convex) throw NotConvexError(report.message);
  auto base = MakeMesh(model);
  auto g = std::shared_ptr<Geometry>(new Geometry(*base));
  g->kind_ = ShapeKind::kConvexMesh;
  const TriangleMesh& mesh = model->mesh();
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Vector3& n = model->face_normals()[f];
    if (n.squaredNorm() < 0.5) continue;
    g->face_normals_M_.push_back(n);
    g->face_offsets_.push_back(n.dot(mesh.vertices[mesh.triangles[f][0]]));
  }
  g->contains_tol_ = 1e-10 * g->radius_;
  return g;
}

Vector3 Geometry::CoreSupport(const Vector3& u_M) const {
  switch (kind_) {
    case ShapeKind::kSphere: return Vector3::Zero();
    case ShapeKind::kCapsule: return Vector3(0, 0, Sign(u_M.z()) * capsule_.half_length);
    default: return Support(u_M);
  }
}

Vector3 Geometry::Support(const Vector3& u_M) const {
  switch (kind_) {
    case ShapeKind::kHalfSpace:
      throw std::logic_error("Geometry::Support is not defined for a half-space");
    case ShapeKind::kSphere: {
      const double n = u_M.norm();
      return n > 0.0 ? Vector3(u_M * (sphere_.radius / n)) : Vector3(0, 0, sphere_.radius);
    }
    case ShapeKind::kBox:
      return Vector3(Sign(u_M.x()) * box_.half_extents.x(), Sign(u_M.y()) * box_.half_extents.y(),
                     Sign(u_M.z()) * box_.half_extents.z());
    case ShapeKind::kCapsule: {
      const double n = u_M.norm();
      const Vector3 core(0, 0, Sign(u_M.z()) * capsule_.half_length);
      return n > 0.0 ? Vector3(core + u_M * (capsule_.radius / n)) : core;
    }
    case ShapeKind::kCylinder: {
      const double nxy = std::hypot(u_M.x(), u_M.y());
      const double z = Sign(u_M.z()) * cylinder_.half_length;
      if (nxy <= 0.0) return Vector3(cylinder_.radius, 0, z);
      const double s = cylinder_.radius / nxy;
      return Vector3(u_M.x() * s, u_M.y() * s, z);
    }
    case ShapeKind::kConvexMesh:
    case ShapeKind::kMesh: {
      const Vector3* best = &hull_points_M_[0];
      double best_h = u_M.dot(*best);
      for (const Vector3& v : hull_points_M_) {
        const double h = u_M.dot(v);
        if (h > best_h) best_h = h, best = &v;
      }
      return *best;
    }
  }
  return Vector3::Zero();
}

bool Geometry::Contains(const Vector3& p_M) const {
  switch (kind_) {
    case ShapeKind::kHalfSpace: return p_M.z() <= 0.0;
    case ShapeKind::kSphere: return p_M.squaredNorm() <= sphere_.radius * sphere_.radius;
    case ShapeKind::kBox: return (p_M.cwiseAbs() - box_.half_extents).maxCoeff() <= 0.0;
    case ShapeKind::kCapsule: {
      const double z = std::clamp(p_M.z(), -capsule_.half_length, capsule_.half_length);
      return (p_M - Vector3(0, 0, z)).squaredNorm() <= capsule_.radius * capsule_.radius;
    }
    case ShapeKind::kCylinder:
      return std::abs(p_M.z()) <= cylinder_.half_length &&
             p_M.x() * p_M.x() + p_M.y() * p_M.y() <= cylinder_.radius * cylinder_.radius;
    case ShapeKind::kConvexMesh:
      for (size_t f = 0; f < face_normals_M_.size(); ++f)
        if (face_normals_M_[f].dot(p_M) - face_offsets_[f] > contains_tol_) return false;
      return true;
    case ShapeKind::kMesh: return model_->closed() && PointInsideMesh(*model_, p_M);
  }
  return false;
}

void Geometry::RequireKind(ShapeKind kind, const char* accessor) const {
  if (kind_ != kind) throw std::logic_error(std::string("Geometry::") + accessor + "() on " + Describe());
}
const Sphere& Geometry::sphere() const { return RequireKind(ShapeKind::kSphere, "sphere"), sphere_; }
const Box& Geometry::box() const { return RequireKind(ShapeKind::kBox, "box"), box_; }
const Capsule& Geometry::capsule() const { return RequireKind(ShapeKind::kCapsule, "capsule"), capsule_; }
const Cylinder& Geometry::cylinder() const {
  return RequireKind(ShapeKind::kCylinder, "cylinder"), cylinder_;
}

std::string Geometry::Describe() const {
  std::ostringstream s;
  s << ShapeKindName(kind_);
  switch (kind_) {
    case ShapeKind::kHalfSpace: break;
    case ShapeKind::kSphere: s << "(radius=" << sphere_.radius << ")"; break;
    case ShapeKind::kBox:
      s << "(half_extents=" << box_.half_extents.x() << "," << box_.half_extents.y() << ","
        << box_.half_extents.z() << ")";
      break;
    case ShapeKind::kCapsule:
      s << "(radius=" << capsule_.radius << ", half_length=" << capsule_.half_length << ")";
      break;
    case ShapeKind::kCylinder:
      s << "(radius=" << cylinder_.radius << ", half_length=" << cylinder_.half_length << ")";
      break;
    case ShapeKind::kConvexMesh:
    case ShapeKind::kMesh: s << " '" << model_->mesh().name << "'"; break;
  }
  return s.str();
}

}  // namespace pd
