// A main() for the fuzz targets without libFuzzer: every file named on the command line,
// and every regular file inside a folder named there (sorted, so runs repeat), is passed to
// LLVMFuzzerTestOneInput once. A property that fails aborts, so ctest reports the input.
// With `--selectors N` first, each input is run N times, with each byte 0..N-1 put in front
// of it (the targets read machine and layout from the first byte): a plain CL job or NC
// program then serves as a seed for every combination. Ends with "N inputs replayed".
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<std::string> inputs;
  int selectors = 0;
  int first = 1;
  if (argc > 2 && std::string(argv[1]) == "--selectors") {
    selectors = std::stoi(argv[2]);
    first = 3;
  }
  for (int i = first; i < argc; ++i) {
    std::error_code ec;
    if (fs::is_directory(argv[i], ec)) {
      std::vector<std::string> in_dir;
      for (const fs::directory_entry& e : fs::recursive_directory_iterator(argv[i]))
        if (e.is_regular_file()) in_dir.push_back(e.path().string());
      std::sort(in_dir.begin(), in_dir.end());
      inputs.insert(inputs.end(), in_dir.begin(), in_dir.end());
    } else if (fs::is_regular_file(argv[i], ec)) {
      inputs.push_back(argv[i]);
    } else {
      std::fprintf(stderr, "replay: no file or folder '%s'\n", argv[i]);
      return 2;
    }
  }
  if (inputs.empty()) {
    std::fprintf(stderr, "replay: no inputs\n");
    return 2;
  }
  std::size_t runs = 0;
  for (const std::string& path : inputs) {
    const std::string data = twinpost::fuzz::read_all(path);
    for (int k = 0; k < std::max(selectors, 1); ++k) {
      const std::string input = selectors > 0 ? std::string(1, static_cast<char>(k)) + data : data;
      std::fprintf(stderr, "replay: %s (selector %d)\n", path.c_str(), selectors > 0 ? k : -1);
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
      ++runs;
    }
  }
  std::printf("%zu inputs replayed\n", runs);
  return 0;
}
