#include "probes/trajectory/trajectory_csv.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <ostream>
#include <string_view>
#include <vector>

#include "probes/trajectory/input_error.h"

namespace probes {
namespace {

constexpr const char* kFieldNames[8] = {"time", "x", "y", "z", "qw", "qx", "qy", "qz"};

std::string_view Trim(std::string_view s) {
  const char* blanks = " \t\r\n";
  const size_t first = s.find_first_not_of(blanks);
  if (first == std::string_view::npos) return {};
  const size_t last = s.find_last_not_of(blanks);
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> SplitCommas(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(Trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

[[noreturn]] void Fail(const std::string& source, int line, const std::string& what) {
  throw InputError(source + ":" + std::to_string(line) + ": " + what);
}

double ParseField(std::string_view text, const std::string& source, int line, int field) {
  const std::string name = kFieldNames[field];
  if (text.empty()) Fail(source, line, "field '" + name + "' is empty");
  // strtod rather than from_chars: it returns subnormals (1e-310) instead of
  // calling them out of range, and overflow as inf, refused just below.
  const std::string copy(text);
  char* end = nullptr;
  const double value = std::strtod(copy.c_str(), &end);
  // (Hexadecimal floats, which strtod also reads, are refused too.)
  if (end != copy.c_str() + copy.size() || std::isspace(static_cast<unsigned char>(copy[0])) ||
      copy.find_first_of("xX") != std::string::npos) {
    Fail(source, line, "field '" + name + "': '" + copy + "' is not a number");
  }
  if (!std::isfinite(value)) {
    Fail(source, line, "field '" + name + "': '" + std::string(text) + "' is not finite");
  }
  return value;
}

bool IsSkippable(std::string_view line) {
  const std::string_view t = Trim(line);
  return t.empty() || t.front() == '#';
}

}  // namespace

Trajectory ParseTrajectoryCsv(std::istream& in, const std::string& source) {
  std::string line;
  int line_number = 0;
  // Header: the first line that is not blank or a comment.
  bool have_header = false;
  while (!have_header && std::getline(in, line)) {
    ++line_number;
    if (IsSkippable(line)) continue;
    std::string normalised;
    for (std::string_view f : SplitCommas(line)) {
      if (!normalised.empty()) normalised += ',';
      normalised += f;
    }
    if (normalised != kTrajectoryCsvHeader) {
      Fail(source, line_number, std::string("header must be '") + kTrajectoryCsvHeader +
                                    "', got '" + std::string(Trim(line)) + "'");
    }
    have_header = true;
  }
  if (!have_header) {
    throw InputError(source + ": empty file, expected the header '" +
                     std::string(kTrajectoryCsvHeader) + "'");
  }

  Trajectory trajectory;
  int previous_line = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (IsSkippable(line)) continue;
    const std::vector<std::string_view> fields = SplitCommas(line);
    if (fields.size() != 8) {
      Fail(source, line_number,
           "expected 8 fields (" + std::string(kTrajectoryCsvHeader) + "), got " +
               std::to_string(fields.size()));
    }
    double v[8];
    for (int i = 0; i < 8; ++i) v[i] = ParseField(fields[i], source, line_number, i);

    PoseSample s;
    s.t = v[0];
    if (!trajectory.empty() && !(s.t > trajectory.back().t)) {
      Fail(source, line_number,
           "field 'time': " + std::string(fields[0]) + " s is not after " +
               std::to_string(trajectory.back().t) + " s on line " +
               std::to_string(previous_line) + " (times must strictly increase)");
    }
    s.p_WP = {v[1], v[2], v[3]};
    const double norm = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
    if (std::abs(norm - 1.0) > kCsvQuaternionNormTol) {
      Fail(source, line_number,
           "quaternion (qw,qx,qy,qz) has norm " + std::to_string(norm) +
               ", not within 1e-3 of 1");
    }
    s.q_WP = {v[4] / norm, v[5] / norm, v[6] / norm, v[7] / norm};
    trajectory.push_back(s);
    previous_line = line_number;
  }
  if (in.bad()) throw InputError(source + ": read error after line " + std::to_string(line_number));
  if (trajectory.empty()) throw InputError(source + ": no samples after the header");
  return trajectory;
}

Trajectory ReadTrajectoryCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open trajectory CSV");
  return ParseTrajectoryCsv(in, path);
}

void WriteTrajectoryCsv(std::ostream& out, const Trajectory& trajectory) {
  out << kTrajectoryCsvHeader << '\n';
  char row[256];
  for (const PoseSample& s : trajectory) {
    std::snprintf(row, sizeof(row), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", s.t,
                  s.p_WP[0], s.p_WP[1], s.p_WP[2], s.q_WP[0], s.q_WP[1], s.q_WP[2], s.q_WP[3]);
    out << row;
  }
}

}  // namespace probes
