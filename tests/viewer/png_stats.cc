// png_stats: pixel content of a PNG, so tests judge pictures by what they
// show rather than by their existence.
//   png_stats FILE [NAME=RRGGBB ...]
// Prints "size W H", "background RRGGBB FRACTION" (the most common colour),
// "foreground FRACTION" (pixels off the background by more than 24 in any
// channel), "colours N" (distinct colours), and for each NAME=RRGGBB the
// fraction of pixels of that hue: same chromaticity r/(r+g+b), g/(r+g+b)
// within 0.035 and at least 15% of its brightness, so shaded surfaces of one
// base colour count (Lambert shading scales all channels alike).
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace {

struct Rgb { int r, g, b; };

bool SameHue(const Rgb& p, const Rgb& ref) {
  const double sp = p.r + p.g + p.b, sr = ref.r + ref.g + ref.b;
  if (sp < 0.15 * sr || sp <= 0) return false;
  return std::abs(p.r / sp - ref.r / sr) < 0.035 && std::abs(p.g / sp - ref.g / sr) < 0.035;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: png_stats FILE [NAME=RRGGBB ...]\n");
    return 2;
  }
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, argv[1])) {
    std::fprintf(stderr, "png_stats: %s: %s\n", argv[1], image.message);
    return 1;
  }
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> px(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, px.data(), 0, nullptr)) {
    std::fprintf(stderr, "png_stats: %s: %s\n", argv[1], image.message);
    return 1;
  }
  const size_t n = static_cast<size_t>(image.width) * image.height;
  std::map<int, size_t> counts;
  for (size_t i = 0; i < n; ++i) ++counts[(px[3 * i] << 16) | (px[3 * i + 1] << 8) | px[3 * i + 2]];
  int bg = 0;
  size_t bg_count = 0;
  for (const auto& [c, k] : counts) {
    if (k > bg_count) bg = c, bg_count = k;
  }
  const Rgb bgc{bg >> 16, (bg >> 8) & 255, bg & 255};
  size_t fg = 0;
  for (size_t i = 0; i < n; ++i) {
    if (std::abs(px[3 * i] - bgc.r) > 24 || std::abs(px[3 * i + 1] - bgc.g) > 24 ||
        std::abs(px[3 * i + 2] - bgc.b) > 24) {
      ++fg;
    }
  }
  std::printf("size %u %u\nbackground %06x %.4f\nforeground %.4f\ncolours %zu\n", image.width,
              image.height, bg, double(bg_count) / n, double(fg) / n, counts.size());
  for (int a = 2; a < argc; ++a) {
    const std::string arg = argv[a];
    const size_t eq = arg.find('=');
    if (eq == std::string::npos || arg.size() - eq - 1 != 6) {
      std::fprintf(stderr, "png_stats: '%s' is not NAME=RRGGBB\n", argv[a]);
      return 2;
    }
    const long v = std::strtol(arg.substr(eq + 1).c_str(), nullptr, 16);
    const Rgb ref{int(v >> 16), int((v >> 8) & 255), int(v & 255)};
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) k += SameHue({px[3 * i], px[3 * i + 1], px[3 * i + 2]}, ref) ? 1 : 0;
    std::printf("hue %s %.5f\n", arg.substr(0, eq).c_str(), double(k) / n);
  }
  return 0;
}
