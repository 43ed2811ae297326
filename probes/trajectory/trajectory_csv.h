#pragma once
// Trajectory CSV: a header line `time,x,y,z,qw,qx,qy,qz` then one sample per
// line: time (s, strictly increasing), p_WP (m), q_WP (w, x, y, z). Blank
// lines and lines starting with '#' are skipped. Velocities are not stored.
#include <iosfwd>
#include <string>

#include "probes/trajectory/pose_sample.h"

namespace probes {

inline constexpr const char* kTrajectoryCsvHeader = "time,x,y,z,qw,qx,qy,qz";
// Quaternions whose norm is further than this from 1 are refused, the others
// normalised: CSV rounding leaves the norm ~1e-9 off, a typo leaves it far off.
inline constexpr double kCsvQuaternionNormTol = 1e-3;

// Parses a whole CSV stream; `source` names it in errors. Throws InputError
// naming source, line number (counting every line from 1), field and value.
Trajectory ParseTrajectoryCsv(std::istream& in, const std::string& source);

// Opens and parses a file; a missing or unreadable file is an InputError.
Trajectory ReadTrajectoryCsv(const std::string& path);

// Writes the header and samples (time in µs resolution, poses to 9 digits).
void WriteTrajectoryCsv(std::ostream& out, const Trajectory& trajectory);

}  // namespace probes
