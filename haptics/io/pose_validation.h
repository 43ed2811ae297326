#pragma once
// Checks each incoming probe pose before it may move anything: finite
// numbers, a unit quaternion (|norm - 1| <= tolerance, so also not zero) and a
// position inside the device workspace. Rejections are counted by reason;
// the last good pose is kept.
#include <cstdint>

#include "haptics/io/pose_sample.h"

namespace haptics {

enum class PoseRejection { kNone, kNonFinite, kBadQuaternion, kOutsideWorkspace };
const char* PoseRejectionName(PoseRejection r);

struct PoseRejectionCounts {
  int64_t non_finite = 0;
  int64_t bad_quaternion = 0;
  int64_t outside_workspace = 0;
  int64_t total() const { return non_finite + bad_quaternion + outside_workspace; }
};

class PoseValidator {
 public:
  // Workspace box in W (m), min < max per axis.
  PoseValidator(const Vector3& workspace_min, const Vector3& workspace_max,
                double quaternion_tolerance = 1e-3);

  // Why `pose` would be rejected (kNone: acceptable). Pure.
  PoseRejection Check(const PoseSample& pose) const;

  // Check, count, and on success keep it (quaternion normalised) as last_good.
  bool Accept(const PoseSample& pose);

  bool has_good() const { return has_good_; }
  const PoseSample& last_good() const { return last_good_; }
  const PoseRejectionCounts& rejections() const { return rejections_; }
  int64_t accepted() const { return accepted_; }

 private:
  Vector3 min_, max_;
  double quaternion_tolerance_;
  bool has_good_ = false;
  PoseSample last_good_;
  PoseRejectionCounts rejections_;
  int64_t accepted_ = 0;
};

}  // namespace haptics
