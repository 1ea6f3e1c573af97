// libFuzzer target for one reader: GG_FUZZ_KIND (0 points, 1 mesh, 2 grid, 3 .poly) and GG_FUZZ_EXT
// (the format's extension) pick it. The input is the file. A gpugeom::Error is the expected answer
// to garbage; anything else (a crash, a sanitizer report, another exception) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gpugeom/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string body(reinterpret_cast<const char*>(data), size);
  try {
    if (GG_FUZZ_KIND == 0) gpugeom::io::parse_points(body, GG_FUZZ_EXT, "fuzz");
    if (GG_FUZZ_KIND == 1) gpugeom::io::parse_mesh(body, GG_FUZZ_EXT, "fuzz");
    if (GG_FUZZ_KIND == 2) gpugeom::io::parse_grid(body, GG_FUZZ_EXT, "fuzz");
    if (GG_FUZZ_KIND == 3) gpugeom::io::parse_poly(body, "fuzz.poly");
  } catch (const gpugeom::Error&) {
  }
  return 0;
}
