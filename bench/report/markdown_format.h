#pragma once
// Number formatting shared by the Markdown writers; "-" for unmeasured (NaN).
#include <cmath>
#include <cstdio>
#include <string>

namespace pd_bench {

inline std::string F(double v, int digits = 1) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}
inline std::string Pct(double fraction, int digits = 2) {
  return std::isnan(fraction) ? "-" : F(100.0 * fraction, digits) + "%";
}
inline std::string G(double v) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace pd_bench
