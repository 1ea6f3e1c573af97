// The CSV every benchmark driver and anchor appends to (plot.py reads it), and the small
// helpers the drivers share.
#pragma once
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"

namespace gpugeom::bench {

// "all", "cpu" or "cuda": the backends to time, CUDA only where a device is usable.
inline std::vector<Backend> backends(const std::string& which) {
  std::vector<Backend> b;
  if (which == "all" || which == "cpu") b.push_back(Backend::Cpu);
  if ((which == "all" || which == "cuda") && query_device().available) b.push_back(Backend::Cuda);
  return b;
}

// --save DIR: the inputs' folder, made where it is missing; false (said on stdout) where it
// cannot be (a driver writing into a missing folder aborted with the library's uncaught error).
inline bool make_save_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) std::cout << "--save: cannot make the folder '" << dir << "': " << ec.message() << "\n";
  return !ec;
}

// "1024,2048,1e6" -> {1024, 2048, 1000000}
inline std::vector<double> numbers(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');)
    if (!x.empty()) v.push_back(std::stod(x));
  return v;
}

// A counter-based hash (splitmix64's finaliser): the same pseudo-random grid for every backend
// and run, generated in parallel.
inline std::uint64_t hash64(std::uint64_t i, std::uint64_t seed) {
  std::uint64_t z = i * 0x9e3779b97f4a7c15ull + seed;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// A phase's time in a run's Stats, 0 when the run had no such phase.
inline double phase_ms(const RunStats& s, const char* name) {
  for (auto& p : s.phase_ms)
    if (p.first == name) return p.second;
  return 0;
}

// Every phase and counter of a run, as two comment lines (the benchmarks' --verbose).
inline void print_stats_lines(const RunStats& s) {
  std::printf("#   phases:");
  for (auto& p : s.phase_ms) std::printf(" %s %.1f", p.first.c_str(), p.second);
  std::printf("\n#   counters:");
  for (auto& c : s.counter_map()) std::printf(" %s %lld", c.first.c_str(), (long long)c.second);
  std::printf("\n");
}

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
