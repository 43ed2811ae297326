// Regression driver for the fuzz targets, built with the normal compiler (no
// libFuzzer): runs LLVMFuzzerTestOneInput on every file named on the command
// line or found (recursively) in a directory named there, so the seed corpus
// and every kept crash input stay tested in the normal suite. A contract
// violation aborts the process (CTest reports the failure); otherwise prints
// how many inputs ran and exits 0. Refuses an empty run (nothing tested).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

int RunFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "fuzz replay: cannot read %s\n", file.c_str());
    return 1;
  }
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::printf("fuzz replay: %s (%zu bytes)\n", file.c_str(), bytes.size());
  std::fflush(stdout);
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  int inputs = 0, errors = 0;
  for (int a = 1; a < argc; ++a) {
    const fs::path arg(argv[a]);
    if (fs::is_directory(arg)) {
      std::vector<fs::path> files;
      for (const auto& entry : fs::recursive_directory_iterator(arg))
        if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
      std::sort(files.begin(), files.end());
      for (const fs::path& f : files) errors += RunFile(f), ++inputs;
    } else if (fs::is_regular_file(arg)) {
      errors += RunFile(arg), ++inputs;
    } else {
      std::fprintf(stderr, "fuzz replay: %s is neither a file nor a directory\n", argv[a]);
      ++errors;
    }
  }
  std::printf("fuzz replay: %d inputs, %d unreadable\n", inputs, errors);
  if (inputs == 0) {
    std::fprintf(stderr, "fuzz replay: no inputs found: nothing was tested\n");
    return 1;
  }
  return errors == 0 ? 0 : 1;
}
