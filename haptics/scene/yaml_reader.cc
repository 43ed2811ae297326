#include "haptics/scene/yaml_reader.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace haptics {
namespace {

std::string FormatNumber(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

bool Range::Contains(double x) const {
  if (!std::isfinite(x)) return false;
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

std::string Range::Describe() const {
  std::string s = (lo_open ? "(" : "[") + FormatNumber(lo) + ", " + FormatNumber(hi) +
                  (hi_open ? ")" : "]");
  if (!unit.empty()) s += " " + unit;
  return s;
}

void YamlSource::Fail(const std::string& key, const std::string& problem) const {
  throw ConfigError(file, key, problem);
}

void YamlSource::Warn(const std::string& key, const std::string& problem) const {
  const std::string message = file + ": " + (key.empty() ? "" : key + ": ") + problem;
  spdlog::warn("{}", message);
  if (warnings) warnings->push_back(message);
}

YAML::Node LoadYamlFile(const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw ConfigError(file, "", "cannot read: no such file");
  try {
    return YAML::LoadFile(file);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(file, "",
                      "YAML syntax error at line " + std::to_string(e.mark.line + 1) +
                          ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ConfigError(file, "", std::string("cannot read: ") + e.what());
  }
}

std::string DescribeNode(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence: return "a list of " + std::to_string(node.size());
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined: break;
  }
  return "nothing";
}

double ReadNumber(const YAML::Node& node, const std::string& key, const Range& range,
                  const YamlSource& src) {
  const std::string expected = "must be a number in " + range.Describe();
  if (!node.IsScalar()) src.Fail(key, expected + ", got " + DescribeNode(node));
  double x = 0.0;
  if (!YAML::convert<double>::decode(node, x))
    src.Fail(key, expected + ", got " + DescribeNode(node));
  if (!range.Contains(x)) src.Fail(key, expected + ", got " + DescribeNode(node));
  return x;
}

int ReadInteger(const YAML::Node& node, const std::string& key, int lo, int hi,
                const YamlSource& src) {
  const std::string expected =
      "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  long long x = 0;
  if (!node.IsScalar() || !YAML::convert<long long>::decode(node, x) || x < lo || x > hi)
    src.Fail(key, expected + ", got " + DescribeNode(node));
  return static_cast<int>(x);
}

Vector3 ReadVector3(const YAML::Node& node, const std::string& key, const Range& range,
                    const YamlSource& src) {
  if (!node.IsSequence() || node.size() != 3)
    src.Fail(key, "must be a list of 3 numbers in " + range.Describe() + ", got " +
                      DescribeNode(node));
  Vector3 v;
  for (int i = 0; i < 3; ++i)
    v[i] = ReadNumber(node[i], key + "[" + std::to_string(i) + "]", range, src);
  return v;
}

YamlMap::YamlMap(const YAML::Node& node, std::string path, const YamlSource* src)
    : node_(node), path_(std::move(path)), src_(src) {
  if (!node_.IsMap())
    src_->Fail(path_, "must be a map of keys, got " + DescribeNode(node_));
}

std::string YamlMap::Path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool YamlMap::Has(const std::string& key) const {
  known_.insert(key);
  const YAML::Node child = node_[key];
  return child.IsDefined() && !child.IsNull();
}

YAML::Node YamlMap::Get(const std::string& key, const std::string& expected) const {
  if (!Has(key)) src_->Fail(Path(key), "missing required key (" + expected + ")");
  return node_[key];
}

double YamlMap::Number(const std::string& key, const Range& range) const {
  return ReadNumber(Get(key, "a number in " + range.Describe()), Path(key), range, *src_);
}

double YamlMap::NumberOr(const std::string& key, double fallback, const Range& range) const {
  return Has(key) ? Number(key, range) : fallback;
}

int YamlMap::Integer(const std::string& key, int lo, int hi) const {
  const std::string expected = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return ReadInteger(Get(key, expected), Path(key), lo, hi, *src_);
}

int YamlMap::IntegerOr(const std::string& key, int fallback, int lo, int hi) const {
  return Has(key) ? Integer(key, lo, hi) : fallback;
}

std::string YamlMap::String(const std::string& key) const {
  const YAML::Node n = Get(key, "a non-empty string");
  if (!n.IsScalar() || n.Scalar().empty())
    src_->Fail(Path(key), "must be a non-empty string, got " + DescribeNode(n));
  return n.Scalar();
}

std::string YamlMap::StringOr(const std::string& key, const std::string& fallback) const {
  return Has(key) ? String(key) : fallback;
}

std::string YamlMap::Choice(const std::string& key, const std::vector<std::string>& choices) const {
  std::string allowed;
  for (const std::string& c : choices) allowed += (allowed.empty() ? "" : ", ") + c;
  const YAML::Node n = Get(key, "one of: " + allowed);
  if (n.IsScalar()) {
    for (const std::string& c : choices)
      if (n.Scalar() == c) return c;
  }
  src_->Fail(Path(key), "must be one of: " + allowed + "; got " + DescribeNode(n));
}

Vector3 YamlMap::Vector(const std::string& key, const Range& range) const {
  return ReadVector3(Get(key, "a list of 3 numbers in " + range.Describe()), Path(key), range,
                     *src_);
}

Vector3 YamlMap::VectorOr(const std::string& key, const Vector3& fallback, const Range& range) const {
  return Has(key) ? Vector(key, range) : fallback;
}

YamlMap YamlMap::Map(const std::string& key) const {
  return YamlMap(Get(key, "a map"), Path(key), src_);
}

void YamlMap::WarnUnknownKeys() const {
  for (const auto& item : node_) {
    const std::string key = item.first.IsScalar() ? item.first.Scalar() : DescribeNode(item.first);
    if (!known_.count(key)) src_->Warn(Path(key), "unknown key, ignored");
  }
}

}  // namespace haptics
