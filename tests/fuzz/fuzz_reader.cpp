// libFuzzer target for the readers. The first byte picks the format (and so the parser); the
// rest is the file. A gpugeom::Error is the expected answer to garbage; anything else (a crash,
// a sanitizer report, another exception) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gpugeom/io.hpp"

#ifndef GG_FUZZ_KIND
#define GG_FUZZ_KIND 0
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const char* kPoints[] = {".xyz", ".csv", ".ply", ".off", ".obj", ".node", ".npy"};
  static const char* kMesh[] = {".ply", ".off", ".obj", ".ele", ".vtu", ".npy"};
  static const char* kGrid[] = {".pgm", ".pbm", ".png", ".npy"};
  if (size == 0) return 0;
  const std::string body(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    if (GG_FUZZ_KIND == 0) gpugeom::io::parse_points(body, kPoints[data[0] % 7], "fuzz");
    if (GG_FUZZ_KIND == 1) gpugeom::io::parse_mesh(body, kMesh[data[0] % 6], "fuzz");
    if (GG_FUZZ_KIND == 2) gpugeom::io::parse_grid(body, kGrid[data[0] % 4], "fuzz");
  } catch (const gpugeom::Error&) {
  }
  return 0;
}
