#pragma once
// A picture of a replay session: a PNG (gnuplot, pngcairo) of the result CSV
// (replay_result_csv.h) with five panels over trajectory time: |force|,
// |torque|, penetration depth, contact count and pose-to-wrench round trip.
// The gnuplot script is kept beside the PNG (PNG path + ".gp") so the plot
// can be redone or restyled; gnuplot's messages go to PNG path + ".log".
#include <string>

namespace probes {

// Default PNG path for a result CSV: the same path with ".png" instead of ".csv".
std::string SessionPlotPath(const std::string& csv_path);

// Runs gnuplot. Returns false and sets *error (naming the file, or saying
// that gnuplot is missing: Debian package gnuplot-nox) on failure.
bool WriteSessionPlot(const std::string& csv_path, const std::string& png_path,
                      const std::string& title, std::string* error);

}  // namespace probes
