// Backend and method names, parsing and resolution (Auto, GPUGEOM_BACKEND), shared by every
// module.
#include <iterator>
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>

#include "exec/deliver.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom {

const char* backend_name(Backend b) {
  static constexpr const char* names[] = {"auto", "cpu", "cuda"};  // (Backend's order)
  const auto i = std::size_t(b);
  return i < std::size(names) ? names[i] : "?";
}

Backend parse_backend(const std::string& s) {
  std::string l(s);
  std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return std::tolower(c); });
  if (l == "auto") return Backend::Auto;
  if (l == "cpu") return Backend::Cpu;
  if (l == "cuda" || l == "gpu") return Backend::Cuda;
  throw Error(ErrorCode::InvalidArgument,
              "unknown backend '" + s + "': expected one of auto, cpu, cuda");
}

const char* method_name(Method m) {
  return m == Method::Digital ? "digital" : "incremental";
}

Method parse_method(const std::string& s) {
  std::string l(s);
  std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return std::tolower(c); });
  if (l == "incremental") return Method::Incremental;
  if (l == "digital") return Method::Digital;
  throw Error(ErrorCode::InvalidArgument,
              "unknown method '" + s + "': expected one of incremental, digital");
}

Backend resolve_backend(Backend requested, int device) {
  if (requested == Backend::Auto) {
    if (const char* env = std::getenv("GPUGEOM_BACKEND"); env && *env) {
      requested = parse_backend(env);
    }
  }
  if (requested == Backend::Cpu) return Backend::Cpu;
  DeviceInfo d = query_device(device);
  // A device named explicitly is a request for CUDA: never a silent fall back to the CPU.
  if (requested == Backend::Cuda || device >= 0) {
    if (!d.available) {
      const bool no_such = device >= 0 && d.device_count > 0 && device >= d.device_count;
      throw Error(no_such ? ErrorCode::InvalidArgument : ErrorCode::Unsupported,
                  "the CUDA backend" + (device >= 0 ? " on device " + std::to_string(device) : "") +
                      " was requested but cannot be used: " + d.reason +
                      " (use --backend cpu or GPUGEOM_BACKEND=cpu)");
    }
    return Backend::Cuda;
  }
  return d.available ? Backend::Cuda : Backend::Cpu;
}

Backend device_entry_backend(Backend requested, int device, const char* entry) {
  if (requested == Backend::Cpu) return Backend::Cpu;
  const DeviceInfo d = query_device(device);
  if (!d.available)
    throw Error(ErrorCode::Unsupported, std::string(entry) + ": no CUDA device can be used here (" +
                                            d.reason +
                                            "); ask for Backend::Cpu to run it on host memory");
  return Backend::Cuda;
}

const char* error_code_name(ErrorCode c) {
  static constexpr const char* names[] = {// (ErrorCode's order)
                                          "invalid argument", "invalid input", "degenerate input",
                                          "parse error",      "I/O error",     "unsupported",
                                          "out of memory",    "CUDA error",    "internal error"};
  const auto i = std::size_t(c);
  return i < std::size(names) ? names[i] : "error";
}

double RunStats::total_ms() const {
  double t = 0;
  for (auto& p : phase_ms) t += p.second;
  return t;
}

std::map<std::string, std::int64_t> RunStats::counter_map() const {
  std::map<std::string, std::int64_t> m;
  if (device_peak_bytes) m["device_peak_bytes"] = device_peak_bytes;
  return m;
}

}  // namespace gpugeom
