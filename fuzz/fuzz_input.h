// The fuzz targets' one helper: libFuzzer hands bytes, the project's loaders take paths (they name the file in every
// error), so each input is written to a file in a private folder of this process and loaded from there.
#pragma once

#include <cstdint>
#include <cstdio>
#include <exception>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace shadetwin::fuzz {

/// A folder of this process under $TMPDIR (made once, removed at exit): <dir>/scenes/ for the inputs, and
/// <dir>/assets -> the checkout's assets/ so a scene's "../assets/..." paths resolve as they do for the shipped scenes.
inline const std::filesystem::path& workDir() {
  static const std::filesystem::path dir = [] {
    const char* t = std::getenv("TMPDIR");
    std::string tmpl = std::string(t && *t ? t : "/tmp") + "/shadetwin_fuzz_XXXXXX";
    if (!mkdtemp(tmpl.data())) std::abort();
    const std::filesystem::path d = tmpl;
    std::filesystem::create_directories(d / "scenes");
#ifdef SHADETWIN_SOURCE_DIR
    std::error_code ec;
    std::filesystem::create_directory_symlink(std::filesystem::path(SHADETWIN_SOURCE_DIR) / "assets", d / "assets", ec);
#endif
    static struct Cleanup {
      std::filesystem::path p;
      ~Cleanup() {
        std::error_code ec;
        std::filesystem::remove_all(p, ec);
      }
    } cleanup{d};
    return d;
  }();
  return dir;
}

/// SHADETWIN_FUZZ_EXPECT_VALID=1 (the seed check in ctest): an input that is rejected is a failure, so every seed is
/// known to load (the fuzzer starts from inputs that reach past the first check).
inline void rejected(const std::exception& e) {
  static const bool strict = std::getenv("SHADETWIN_FUZZ_EXPECT_VALID") != nullptr;
  if (strict) {
    std::fprintf(stderr, "seed rejected: %s\n", e.what());
    std::abort();
  }
}

/// Runs one parse: what it throws is the expected answer to bad input (rejected() above); a crash, a sanitizer report or
/// a hang is a bug.
template <class Parse>
void parseOrReject(Parse parse) {
  try {
    parse();
  } catch (const std::exception& e) {
    rejected(e);
  }
}

/// Writes the input to <dir>/scenes/<name> and returns that path.
inline std::string inputFile(const uint8_t* data, size_t size, const std::string& name) {
  const std::filesystem::path p = workDir() / "scenes" / name;
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  f.close();
  if (!f) std::abort();
  return p.string();
}

}  // namespace shadetwin::fuzz
