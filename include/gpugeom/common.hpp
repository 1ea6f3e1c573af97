/// @file
/// Common vocabulary of the public API: points, backends, errors, statistics.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace gpugeom {

/// A 2D point, coordinates as doubles.
struct Point2 {
  double x, y;
};
/// A 3D point, coordinates as doubles.
struct Point3 {
  double x, y, z;
};

/// Which executor runs an algorithm. Auto picks CUDA when the build has it and a device is
/// present; the environment variable GPUGEOM_BACKEND=cpu|cuda overrides Auto.
enum class Backend { Auto, Cpu, Cuda };

/// The backend's name: "auto", "cpu" or "cuda".
const char* backend_name(Backend b);
/// Parses "auto", "cpu", "cuda" (case-insensitive); throws Error(InvalidArgument) otherwise.
Backend parse_backend(const std::string& s);
/// Resolves Auto (and GPUGEOM_BACKEND) to a concrete backend; asking for Cuda where the build
/// or the machine has none throws Error(Unsupported). device: as RunOptions::device.
Backend resolve_backend(Backend requested, int device = -1);
/// True when this build was compiled with CUDA support.
bool built_with_cuda();

class DeviceMemoryResource;  // gpugeom/memory.hpp

namespace detail {
/// The library's own knobs for its tests and benchmarks (defined in the sources, not here).
struct Tuning;
}  // namespace detail

/// Where and how an algorithm runs; every capability's options carry these.
struct RunOptions {
  Backend backend = Backend::Auto;
  /// CUDA: the device (ordinal) and the stream (a cudaStream_t of that device, passed as void*
  /// so this header needs no CUDA). device -1 takes the stream's device, else the calling
  /// thread's current device; stream nullptr takes the calling thread's per-thread default
  /// stream (cudaStreamPerThread), which is ordered after work on the legacy default stream.
  /// The calling thread's current device is restored when the call returns. Several host
  /// threads may run calls at once, each with its own device or stream. A device result gives
  /// its memory back on this stream when its last reference goes, so a stream of the caller's
  /// must outlive the device results of calls on it (as with rmm::device_buffer).
  int device = -1;
  void* stream = nullptr;
  /// CPU: OpenMP threads (0: OpenMP's default for the calling thread). Results do not depend on
  /// it.
  int threads = 0;
  /// Per-phase timings in the statistics synchronise the executor after each phase (slower, exact
  /// attribution); off, phases that overlap are timed as they come.
  bool profile = false;
  /// CUDA: where the call takes its device memory (gpugeom/memory.hpp), every temporary array
  /// and the device results it returns; empty: the library's own pool on the device
  /// (library_memory_resource()). A device result holds the resource until its last reference
  /// is dropped. The CPU executor does not use it.
  std::shared_ptr<DeviceMemoryResource> memory;
  /// The library's internal knobs, set by its own tests and benchmarks (user code leaves it
  /// empty: the library's rules apply). No knob changes a result.
  std::shared_ptr<const detail::Tuning> tuning;
};

/// A capability's options (Options derives from RunOptions) that run as `run` does: its
/// RunOptions part copied, the rest Options' defaults. For passing one call's executor, stream,
/// threads and memory on to another capability, e.g. voronoi2d_device(xy, n, tri,
/// options_from<Voronoi2dOptions>(run)).
template <class Options>
Options options_from(const RunOptions& run) {
  Options o;
  static_cast<RunOptions&>(o) = run;
  return o;
}

/// How a triangulation is computed (issue 20; Delaunay2dOptions::method). Both give exactly
/// the same result (the same triangles for the same points: one simulation of simplicity).
///   Incremental: batches of points inserted, each followed by rounds of parallel flips.
///   Digital: thesis chapter 4's digital method: the digital Voronoi diagram of the points on a
///     grid (PBA), its dual as a sketch, shifted to the points' own coordinates, the points the
///     grid could not place inserted, then flipped until Delaunay.
enum class Method { Incremental, Digital };
/// The method's name: "incremental" or "digital".
const char* method_name(Method m);
/// Parses "incremental", "digital" (case-insensitive); throws Error(InvalidArgument) otherwise.
Method parse_method(const std::string& s);

/// An array the caller provides for an output (SciPy's `distances=` / `indices=` pattern): data
/// and its length in elements. Where a function says so, the output is written there instead of
/// into memory of the library's; a wrong length is refused (Error(InvalidArgument), naming the
/// output and both lengths) before any work.
template <class T>
struct OutBuffer {
  T* data = nullptr;
  std::int64_t size = 0;
  explicit operator bool() const { return data != nullptr; }
};

/// What query_device reports about a CUDA device, and why it cannot be used where it cannot.
struct DeviceInfo {
  bool available = false;  ///< a CUDA device can be used by this build
  int device = -1;         ///< its ordinal
  int device_count = 0;    ///< CUDA devices on this machine
  std::string name;
  int compute_major = 0, compute_minor = 0;
  int multiprocessors = 0;
  std::size_t total_memory = 0, free_memory = 0;
  std::string reason;  ///< why not available, when it is not
};
/// The device given (-1: the calling thread's current device). available is false, with the
/// reason, where it cannot run this build's kernels (no device, too old, or no code built for
/// its architecture).
DeviceInfo query_device(int device = -1);
/// The CUDA architectures this build has device code for, e.g. "sm_90 compute_90" ("" without
/// CUDA).
std::string built_cuda_architectures();
/// Creates the device's CUDA context and the library's memory pool on it ahead of the first
/// computation (-1: the calling thread's current device). A process's first CUDA call takes
/// about a quarter of a second (on the H100 machine); a program can call this on another
/// thread while it reads its input, and its first computation then starts at once. Does
/// nothing where there is no usable device; never throws.
void prepare_device(int device = -1) noexcept;
/// Hands the device memory the library keeps for reuse (its own pool, one per device) back to
/// the driver. Call between phases of a program that needs the memory elsewhere. Blocks whose
/// stream-ordered free has not yet run on its stream stay in the pool (nothing here waits for
/// the device): synchronise the streams of earlier calls first to hand back everything.
void release_cached_device_memory();

/// Every failure the library reports is an Error with one of these codes, so callers can
/// react by kind; the message says what went wrong and what to do about it.
enum class ErrorCode {
  InvalidArgument,  ///< a parameter is out of range or inconsistent
  InvalidInput,     ///< NaN/Inf, too few points, sizes beyond index limits
  DegenerateInput,  ///< e.g. all points collinear / coplanar where that makes the problem void
  Parse,            ///< a file does not follow its format
  Io,               ///< a file cannot be opened, read or written
  Unsupported,      ///< asked for something this build or machine cannot do
  OutOfMemory,      ///< host or device allocation failed
  Cuda,             ///< any other CUDA runtime failure
  Internal,         ///< an invariant of an algorithm failed: a bug, please report it
};
/// The code's name as messages print it, e.g. "invalid input".
const char* error_code_name(ErrorCode c);

/// The exception every failure of the library throws: a code (ErrorCode) and a message saying what
/// to change.
class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& msg) : std::runtime_error(msg), code_(code) {}
  /// The kind of failure.
  ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

/// What every run's statistics hold: where it ran, its phases' times in the order they ran,
/// and the device memory it used. Each capability's statistics derive from it and add their
/// counters as named fields (Delaunay3dStats, Hull3dStats, EdtStats, ...).
struct RunStats {
  Backend backend = Backend::Cpu;
  /// Phase names and times in milliseconds, in the order they ran (a log: some phases repeat
  /// or are named at run time, per axis or per device).
  std::vector<std::pair<std::string, double>> phase_ms;
  /// The CUDA executor's peak device memory over the call, in bytes (from RunOptions::memory's
  /// resource, the library's pool by default); 0 on the CPU executor.
  std::int64_t device_peak_bytes = 0;
  /// The sum of the phases' times in milliseconds.
  double total_ms() const;
  /// The counters by name, device_peak_bytes among them where it is not 0: for printing (the
  /// CLI's --verbose, the benches' tables, Python's stats dict). Programs read the fields.
  virtual std::map<std::string, std::int64_t> counter_map() const;

  RunStats() = default;
  RunStats(const RunStats&) = default;
  RunStats(RunStats&&) = default;
  RunStats& operator=(const RunStats&) = default;
  RunStats& operator=(RunStats&&) = default;
  virtual ~RunStats() = default;
};

}  // namespace gpugeom
