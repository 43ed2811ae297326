#include "pd_core/geometry/parse_pose_line.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace pd {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

std::vector<std::string> SplitFields(std::string_view line) {
  std::vector<std::string> fields;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsBlank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !IsBlank(line[i])) ++i;
    if (i > start) fields.emplace_back(line.substr(start, i - start));
  }
  return fields;
}

PoseLine Error(std::string message) {
  PoseLine out;
  out.kind = PoseLine::Kind::kError;
  out.error = std::move(message);
  return out;
}

}  // namespace

PoseLine ParsePoseLine(std::string_view line) {
  const std::vector<std::string> fields = SplitFields(line);
  if (fields.empty() || fields[0][0] == '#') return PoseLine{};
  if (fields.size() != 7) {
    return Error("expected 7 numbers (x y z qw qx qy qz), got " + std::to_string(fields.size()) +
                 " fields");
  }
  static const char* const kNames[7] = {"x", "y", "z", "qw", "qx", "qy", "qz"};
  double v[7];
  for (int k = 0; k < 7; ++k) {
    const char* begin = fields[k].c_str();
    char* end = nullptr;
    v[k] = std::strtod(begin, &end);
    if (end == begin || *end != '\0')
      return Error("field " + std::string(kNames[k]) + " = '" + fields[k] + "' is not a number");
    // Overflow ("1e999") comes back as inf; underflow as a harmless tiny number.
    if (!std::isfinite(v[k]))
      return Error("field " + std::string(kNames[k]) + " = '" + fields[k] + "' is not finite");
  }
  const double norm = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6]);
  if (!(std::abs(norm - 1.0) <= kQuaternionNormTol)) {
    std::ostringstream msg;
    msg << "quaternion (qw qx qy qz) has norm " << norm << ", not within "
        << kQuaternionNormTol << " of 1";
    return Error(msg.str());
  }
  PoseLine out;
  out.kind = PoseLine::Kind::kPose;
  out.X_WP = MakePose(Vector3(v[0], v[1], v[2]), v[3], v[4], v[5], v[6]);
  return out;
}

}  // namespace pd
