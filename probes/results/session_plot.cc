#include "probes/results/session_plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

extern char** environ;

namespace probes {
namespace {

// A gnuplot single-quoted string ('' is a quote inside it).
std::string Quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

// Columns by the names of the result CSV header (probes/results/replay_result_csv.h);
// unanswered poses have empty fields, which gnuplot skips.
constexpr const char* kPanels = R"GP(
set datafile separator ","
set terminal pngcairo size 1100,1250 noenhanced font ",10"
set multiplot layout 5,1 title title
set grid
set lmargin 12
set xrange [*:*]
set format y "%g"
# Keep curves at zero off the frame.
set offsets graph 0, graph 0, graph 0.06, graph 0.06
sq(a, b, c) = sqrt(a * a + b * b + c * c)
set ylabel "|force| (N)"
plot csv using (column("t")):(sq(column("fx"), column("fy"), column("fz"))) with lines lw 2 lc rgb "#d62728" notitle
set ylabel "|torque| (mN m)"
plot csv using (column("t")):(1e3 * sq(column("tx"), column("ty"), column("tz"))) with lines lw 2 lc rgb "#9467bd" notitle
set ylabel "penetration depth (mm)"
plot csv using (column("t")):(1e3 * column("penetration_depth")) with lines lw 2 lc rgb "#1f77b4" notitle
set ylabel "contact regions"
plot csv using (column("t")):(column("contact_count")) with steps lw 2 lc rgb "#2ca02c" notitle
set ylabel "round trip (us, log)"
set xlabel "trajectory time (s)"
set logscale y
set offsets graph 0, graph 0, 0, 0
plot csv using (column("t")):(column("latency_us")) with points pt 7 ps 0.35 lc rgb "#ff7f0e" notitle
unset multiplot
)GP";

}  // namespace

std::string SessionPlotPath(const std::string& csv_path) {
  const std::string ext = ".csv";
  if (csv_path.size() > ext.size() && csv_path.compare(csv_path.size() - ext.size(), ext.size(), ext) == 0) {
    return csv_path.substr(0, csv_path.size() - ext.size()) + ".png";
  }
  return csv_path + ".png";
}

bool WriteSessionPlot(const std::string& csv_path, const std::string& png_path,
                      const std::string& title, std::string* error) {
  const std::string script_path = png_path + ".gp", log_path = png_path + ".log";
  {
    std::ofstream gp(script_path);
    gp << "# Session plot of " << csv_path << " (written by probe_replay): gnuplot " << script_path << "\n"
       << "csv = " << Quoted(csv_path) << "\ntitle = " << Quoted(title) << "\n"
       << "set output " << Quoted(png_path) << kPanels;
    if (!gp.flush()) {
      *error = script_path + ": cannot write the gnuplot script";
      return false;
    }
  }
  std::remove(png_path.c_str());
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::string prog = "gnuplot";
  char* argv[] = {prog.data(), const_cast<char*>(script_path.c_str()), nullptr};
  pid_t pid = 0;
  const int spawn_error = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) {
    *error = std::string("cannot run gnuplot (Debian package gnuplot-nox): ") + std::strerror(spawn_error);
    return false;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  std::ifstream png(png_path, std::ios::binary | std::ios::ate);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !png || png.tellg() <= 0) {
    *error = "gnuplot failed on " + script_path + " (exit status " +
             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "; its messages: " + log_path + ")";
    return false;
  }
  return true;
}

}  // namespace probes
