#include "pd_core/convex/closed_form_pd.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pd_core/proximity/triangle_geometry.h"

namespace pd {

namespace {

bool IsSweptSphere(ShapeKind k) { return k == ShapeKind::kSphere || k == ShapeKind::kCapsule; }

// A unit vector perpendicular to d (non-zero).
Vector3 Perpendicular(const Vector3& d) { return d.unitOrthogonal(); }

PairPdAnswer Colliding(double depth, const Vector3& n_W) {
  PairPdAnswer a;
  if (!(depth > 0.0)) return a;
  a.in_collision = true;
  a.depth = depth;
  a.normal_W = n_W;
  return a;
}

PairPdAnswer AgainstHalfSpace(const Geometry& P, const Isometry3& X_WP, const Isometry3& X_WS) {
  const Vector3 n_W = X_WS.linear().col(2);
  const double plane = n_W.dot(X_WS.translation());
  const Vector3 p_W = X_WP * P.Support(X_WP.linear().transpose() * (-n_W));
  return Colliding(plane - n_W.dot(p_W), n_W);
}

// Core segment of a sphere (zero length) or capsule in world: start, vector.
void CoreSegment(const Geometry& g, const Isometry3& X_WM, Vector3* start_W, Vector3* d_W) {
  const double h = g.kind() == ShapeKind::kCapsule ? g.capsule().half_length : 0.0;
  const Vector3 axis_W = X_WM.linear().col(2);
  *start_W = X_WM.translation() - h * axis_W;
  *d_W = 2.0 * h * axis_W;
}

PairPdAnswer SweptSpheres(const Geometry& P, const Isometry3& X_WP, const Geometry& S,
                          const Isometry3& X_WS) {
  Vector3 a_P, d_P, a_S, d_S, c_P, c_S;
  CoreSegment(P, X_WP, &a_P, &d_P);
  CoreSegment(S, X_WS, &a_S, &d_S);
  double s, t;
  ClosestSegmentSegment(a_P, a_P + d_P, a_S, a_S + d_S, &s, &t, &c_P, &c_S);
  const Vector3 v = c_P - c_S;
  const double dist = v.norm();
  const double r = P.margin() + S.margin();
  const double size = P.radius() + S.radius();
  if (dist > 1e-12 * size) return Colliding(r - dist, v / dist);
  // Cores cross: PD is r along any direction normal to both cores (the
  // Minkowski difference of the cores is flat, at most a parallelogram).
  Vector3 n = d_P.cross(d_S);
  if (n.norm() <= 1e-12 * (d_P.norm() * d_S.norm()) || n.norm() == 0.0) {
    const Vector3 axis = d_P.squaredNorm() > d_S.squaredNorm() ? d_P : d_S;
    n = axis.squaredNorm() > 0.0 ? Perpendicular(axis) : Vector3(X_WS.linear().col(2));
  } else {
    n.normalize();
  }
  return Colliding(r, n);
}

// Sphere probe against a box scene.
PairPdAnswer SphereBox(const Geometry& P, const Isometry3& X_WP, const Geometry& S,
                       const Isometry3& X_WS) {
  const Vector3 h = S.box().half_extents;
  const double r = P.sphere().radius;
  const Vector3 c_S = X_WS.inverse() * X_WP.translation();
  const Vector3 q_S = c_S.cwiseMax(-h).cwiseMin(h);
  const Vector3 v_S = c_S - q_S;
  const double dist = v_S.norm();
  if (dist > 0.0) return Colliding(r - dist, X_WS.linear() * (v_S / dist));
  // Centre inside the box: out through the nearest face.
  int k = 0;
  (h - c_S.cwiseAbs()).minCoeff(&k);
  Vector3 n_S = Vector3::Zero();
  n_S[k] = c_S[k] < 0.0 ? -1.0 : 1.0;
  return Colliding(r + h[k] - std::abs(c_S[k]), X_WS.linear() * n_S);
}

PairPdAnswer Flipped(PairPdAnswer a) {
  a.normal_W = -a.normal_W;
  return a;
}

}  // namespace

bool HasClosedFormPd(ShapeKind probe, ShapeKind scene) {
  if (probe == ShapeKind::kHalfSpace) return false;
  if (scene == ShapeKind::kHalfSpace) return true;
  if (IsSweptSphere(probe) && IsSweptSphere(scene)) return true;
  return (probe == ShapeKind::kSphere && scene == ShapeKind::kBox) ||
         (probe == ShapeKind::kBox && scene == ShapeKind::kSphere);
}

PairPdAnswer ClosedFormPenetrationDepth(const Geometry& probe, const Isometry3& X_WP,
                                        const Geometry& scene, const Isometry3& X_WS) {
  const ShapeKind kp = probe.kind(), ks = scene.kind();
  if (!HasClosedFormPd(kp, ks))
    throw std::invalid_argument(std::string("no closed-form PD for a ") + ShapeKindName(kp) +
                                " probe against a " + ShapeKindName(ks) + " scene object");
  if (ks == ShapeKind::kHalfSpace) return AgainstHalfSpace(probe, X_WP, X_WS);
  if (IsSweptSphere(kp) && IsSweptSphere(ks)) return SweptSpheres(probe, X_WP, scene, X_WS);
  if (kp == ShapeKind::kSphere) return SphereBox(probe, X_WP, scene, X_WS);
  return Flipped(SphereBox(scene, X_WS, probe, X_WP));
}

}  // namespace pd
