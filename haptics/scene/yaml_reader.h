#pragma once
// Typed, range-checked reading of YAML maps for config files. Every error is a
// ConfigError naming the file, the full key path (coupling.translational.
// stiffness, objects[2].shape.radius) and the allowed values; keys that no
// reader asked about are warned about (spdlog warn, and collected).
#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "haptics/scene/config_error.h"
#include "haptics/tool/spatial.h"

namespace haptics {

// An interval of allowed numbers and their unit, for checks and messages.
struct Range {
  double lo = 0.0, hi = 0.0;
  bool lo_open = false, hi_open = false;
  std::string unit;

  bool Contains(double x) const;
  std::string Describe() const;  // e.g. "(0, 100000] N/m"

  static Range Positive(double hi, std::string unit) { return {0.0, hi, true, false, std::move(unit)}; }
  static Range NonNegative(double hi, std::string unit) { return {0.0, hi, false, false, std::move(unit)}; }
  static Range Closed(double lo, double hi, std::string unit) { return {lo, hi, false, false, std::move(unit)}; }
};

// The file being read and where its warnings go.
struct YamlSource {
  std::string file;
  std::vector<std::string>* warnings = nullptr;

  [[noreturn]] void Fail(const std::string& key, const std::string& problem) const;
  void Warn(const std::string& key, const std::string& problem) const;
};

// Loads a YAML file; ConfigError on a missing file or a syntax error (with line
// and column).
YAML::Node LoadYamlFile(const std::string& file);

// How a node reads in a message: 'text', a list of N, a map, nothing.
std::string DescribeNode(const YAML::Node& node);

// Scalar readers for any node (list elements included); `key` names it.
double ReadNumber(const YAML::Node& node, const std::string& key, const Range& range,
                  const YamlSource& src);
int ReadInteger(const YAML::Node& node, const std::string& key, int lo, int hi,
                const YamlSource& src);
// A list of exactly three numbers, each in `range`.
Vector3 ReadVector3(const YAML::Node& node, const std::string& key, const Range& range,
                    const YamlSource& src);

// A YAML map at key path `path` ("" for the document root).
class YamlMap {
 public:
  YamlMap(const YAML::Node& node, std::string path, const YamlSource* src);

  // Full key path of a child, e.g. "coupling" + "translational".
  std::string Path(const std::string& key) const;
  const std::string& path() const { return path_; }
  const YamlSource& source() const { return *src_; }

  // Each accessor marks `key` as known. Required ones fail with "missing".
  bool Has(const std::string& key) const;
  YAML::Node Get(const std::string& key, const std::string& expected) const;
  double Number(const std::string& key, const Range& range) const;
  double NumberOr(const std::string& key, double fallback, const Range& range) const;
  int Integer(const std::string& key, int lo, int hi) const;
  int IntegerOr(const std::string& key, int fallback, int lo, int hi) const;
  std::string String(const std::string& key) const;  // non-empty
  std::string StringOr(const std::string& key, const std::string& fallback) const;
  // One of `choices`.
  std::string Choice(const std::string& key, const std::vector<std::string>& choices) const;
  Vector3 Vector(const std::string& key, const Range& range) const;
  Vector3 VectorOr(const std::string& key, const Vector3& fallback, const Range& range) const;
  YamlMap Map(const std::string& key) const;

  // Warns about every key no accessor asked about.
  void WarnUnknownKeys() const;

 private:
  const YAML::Node node_;  // const: operator[] must never insert keys
  std::string path_;
  const YamlSource* src_;
  mutable std::set<std::string> known_;
};

}  // namespace haptics
