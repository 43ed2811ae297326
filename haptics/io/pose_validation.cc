#include "haptics/io/pose_validation.h"

#include <cmath>

namespace haptics {

const char* PoseRejectionName(PoseRejection r) {
  switch (r) {
    case PoseRejection::kNone: return "none";
    case PoseRejection::kNonFinite: return "non-finite";
    case PoseRejection::kBadQuaternion: return "non-unit quaternion";
    case PoseRejection::kOutsideWorkspace: return "outside workspace";
  }
  return "unknown";
}

PoseValidator::PoseValidator(const Vector3& workspace_min, const Vector3& workspace_max,
                             double quaternion_tolerance)
    : min_(workspace_min), max_(workspace_max), quaternion_tolerance_(quaternion_tolerance) {}

PoseRejection PoseValidator::Check(const PoseSample& pose) const {
  if (!pose.p_WD.allFinite() || !pose.q_WD.coeffs().allFinite()) return PoseRejection::kNonFinite;
  if (pose.has_velocity && (!pose.v_WD.allFinite() || !pose.w_WD.allFinite()))
    return PoseRejection::kNonFinite;
  if (!(std::abs(pose.q_WD.norm() - 1.0) <= quaternion_tolerance_))
    return PoseRejection::kBadQuaternion;
  if ((pose.p_WD.array() < min_.array()).any() || (pose.p_WD.array() > max_.array()).any())
    return PoseRejection::kOutsideWorkspace;
  return PoseRejection::kNone;
}

bool PoseValidator::Accept(const PoseSample& pose) {
  switch (Check(pose)) {
    case PoseRejection::kNone: break;
    case PoseRejection::kNonFinite: ++rejections_.non_finite; return false;
    case PoseRejection::kBadQuaternion: ++rejections_.bad_quaternion; return false;
    case PoseRejection::kOutsideWorkspace: ++rejections_.outside_workspace; return false;
  }
  last_good_ = pose;
  last_good_.q_WD.normalize();
  has_good_ = true;
  ++accepted_;
  return true;
}

}  // namespace haptics
