// The CSV every benchmark driver and anchor appends to (plot.py reads it).
#pragma once
#include <fstream>
#include <string>

namespace gpugeom::bench {

// Opens path for appending; writes the header when the file is new.
inline std::ofstream open_bench_csv(const std::string& path) {
  std::ofstream f;
  if (path.empty()) return f;
  f.open(path, std::ios::app);
  if (f.tellp() == 0)
    f << "problem,distribution,n,backend,device,upload_ms,compute_ms,download_ms,device_resident_"
         "ms,"
         "with_copies_ms,exact_fraction\n";
  return f;
}

}  // namespace gpugeom::bench
