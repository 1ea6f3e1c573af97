// Common vocabulary of the public API: points, backends, errors, statistics.
#pragma once
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace gpugeom {

struct Point2 {
  double x, y;
};
struct Point3 {
  double x, y, z;
};

// Which executor runs an algorithm. Auto picks CUDA when the build has it and a device is
// present; the environment variable GPUGEOM_BACKEND=cpu|cuda overrides Auto.
enum class Backend { Auto, Cpu, Cuda };

const char* backend_name(Backend b);
// Parses "auto", "cpu", "cuda" (case-insensitive); throws Error(InvalidArgument) otherwise.
Backend parse_backend(const std::string& s);
// Resolves Auto (and GPUGEOM_BACKEND) to a concrete backend; asking for Cuda where the build
// or the machine has none throws Error(Unsupported).
Backend resolve_backend(Backend requested);
// True when this build was compiled with CUDA support.
bool built_with_cuda();

struct DeviceInfo {
  bool available = false;  // a CUDA device can be used by this build
  std::string name;
  int compute_major = 0, compute_minor = 0;
  int multiprocessors = 0;
  std::size_t total_memory = 0, free_memory = 0;
  std::string reason;  // why not available, when it is not
};
DeviceInfo query_device();

// Every failure the library reports is an Error with one of these codes, so callers can
// react by kind; the message says what went wrong and what to do about it.
enum class ErrorCode {
  InvalidArgument,  // a parameter is out of range or inconsistent
  InvalidInput,     // NaN/Inf, too few points, sizes beyond index limits
  DegenerateInput,  // e.g. all points collinear / coplanar where that makes the problem void
  Parse,            // a file does not follow its format
  Io,               // a file cannot be opened, read or written
  Unsupported,      // asked for something this build or machine cannot do
  OutOfMemory,      // host or device allocation failed
  Cuda,             // any other CUDA runtime failure
  Internal,         // an invariant of an algorithm failed: a bug, please report it
};
const char* error_code_name(ErrorCode c);

class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& msg) : std::runtime_error(msg), code_(code) {}
  ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

// Phase timings and counters of one run.
struct Stats {
  Backend backend = Backend::Cpu;
  std::vector<std::pair<std::string, double>> phase_ms;  // in the order they ran
  std::map<std::string, std::int64_t> counters;
  double total_ms() const;
};

}  // namespace gpugeom
