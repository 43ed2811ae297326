#include "probes/trajectory/motion_params.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "probes/trajectory/input_error.h"

namespace probes {
namespace {

std::string Where(const std::string& path, const YAML::Node& node, const std::string& key) {
  // yaml-cpp marks are 0-based.
  return path + ":" + std::to_string(node.Mark().line + 1) + ": key '" + key + "'";
}

double ReadNumber(const std::string& path, const std::string& key, const YAML::Node& node) {
  if (!node.IsScalar()) throw InputError(Where(path, node, key) + ": expected a number");
  try {
    const double v = node.as<double>();
    if (!std::isfinite(v)) throw InputError(Where(path, node, key) + ": value is not finite");
    return v;
  } catch (const YAML::BadConversion&) {
    throw InputError(Where(path, node, key) + ": expected a number, got '" + node.Scalar() + "'");
  }
}

template <size_t N>
std::array<double, N> ReadVector(const std::string& path, const std::string& key,
                                 const YAML::Node& node) {
  if (!node.IsSequence() || node.size() != N) {
    throw InputError(Where(path, node, key) + ": expected a list of " + std::to_string(N) +
                     " numbers");
  }
  std::array<double, N> v{};
  for (size_t i = 0; i < N; ++i) v[i] = ReadNumber(path, key, node[i]);
  return v;
}

[[noreturn]] void Bad(const std::string& field, const std::string& why) {
  throw InputError("motion parameter '" + field + "' " + why);
}

}  // namespace

void LoadMotionParamsYaml(const std::string& path, MotionParams* p) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path + ": cannot open motion parameter file");
  } catch (const YAML::ParserException& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(path + ": expected a mapping of motion parameters");
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node& v = kv.second;
    if (key == "script") {
      if (!v.IsScalar()) throw InputError(Where(path, v, key) + ": expected a script name");
      p->script = v.Scalar();
    } else if (key == "centre") {
      p->centre = ReadVector<3>(path, key, v);
    } else if (key == "amplitude") {
      p->amplitude = ReadNumber(path, key, v);
    } else if (key == "depth") {
      p->depth = ReadNumber(path, key, v);
    } else if (key == "speed") {
      p->speed = ReadNumber(path, key, v);
    } else if (key == "duration") {
      p->duration = ReadNumber(path, key, v);
    } else if (key == "approach") {
      p->approach = ReadNumber(path, key, v);
    } else if (key == "hold") {
      p->hold = ReadNumber(path, key, v);
    } else if (key == "direction") {
      p->direction = ReadVector<3>(path, key, v);
    } else if (key == "orientation") {
      p->orientation = ReadVector<4>(path, key, v);
    } else if (key == "rate_hz") {
      p->rate_hz = ReadNumber(path, key, v);
    } else {
      throw InputError(Where(path, kv.first, key) +
                       ": unknown (known: script, centre, amplitude, depth, speed, duration, "
                       "approach, hold, direction, orientation, rate_hz)");
    }
  }
}

void ValidateMotionParams(MotionParams* p) {
  static const std::set<std::string> kScripts = {"approach_and_press", "slide", "stir",
                                                 "insert_peg"};
  if (kScripts.count(p->script) == 0) {
    Bad("script", "'" + p->script + "' is not one of: " + kScriptNames);
  }
  for (double c : p->centre) {
    if (!std::isfinite(c)) Bad("centre", "has a non-finite component");
  }
  auto require = [](const char* name, double v, bool ok, const char* rule) {
    if (!std::isfinite(v) || !ok) Bad(name, "= " + std::to_string(v) + " must be " + rule);
  };
  const bool lateral = p->script == "slide" || p->script == "stir";
  require("amplitude", p->amplitude, lateral || p->script == "approach_and_press"
                                         ? p->amplitude > 0.0 : p->amplitude >= 0.0,
          lateral || p->script == "approach_and_press" ? "> 0 m for this script" : ">= 0 m");
  require("depth", p->depth, p->depth >= 0.0, ">= 0 m");
  require("speed", p->speed, p->speed > 0.0 && p->speed <= 2.0, "in (0, 2] m/s");
  require("duration", p->duration, p->duration > 0.0 && p->duration <= 3600.0, "in (0, 3600] s");
  require("approach", p->approach, p->approach >= 0.0, ">= 0 m");
  require("hold", p->hold, p->hold >= 0.0, ">= 0 s");
  require("rate_hz", p->rate_hz, p->rate_hz >= 1.0 && p->rate_hz <= 10000.0, "in [1, 10000] Hz");

  const Vec3& d = p->direction;
  const double dn = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!std::isfinite(dn) || dn < 1e-9) Bad("direction", "must be a non-zero vector");
  for (double& c : p->direction) c /= dn;

  const Quat& q = p->orientation;
  const double qn = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!std::isfinite(qn) || std::abs(qn - 1.0) > 1e-3) {
    Bad("orientation", "must be a unit quaternion w,x,y,z (norm " + std::to_string(qn) + ")");
  }
  for (double& c : p->orientation) c /= qn;
}

}  // namespace probes
