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
// An interval of fractions as percentages, "0.10-0.57%".
inline std::string PctRange(double lo, double hi, int digits = 2) {
  if (std::isnan(lo) || std::isnan(hi)) return "-";
  return F(100.0 * lo, digits) + "-" + F(100.0 * hi, digits) + "%";
}
inline std::string G(double v) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace pd_bench
