// Shared pieces of the command-line program: argument access, global options, timing, exit codes.
#pragma once
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::cli {

enum Exit { kOk = 0, kCheckFailed = 1, kUsage = 2, kBadInput = 3, kInternal = 4 };

struct Global {
  Backend backend = Backend::Auto;
  bool verbose = false, quiet = false;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Remaining arguments of a subcommand, consumed as options are recognised.
class Args {
 public:
  explicit Args(std::vector<std::string> a) : a_(std::move(a)) {}
  bool flag(const std::string& name);                     // --name
  bool value(const std::string& name, std::string& out);  // --name V or --name=V
  std::vector<std::string> positionals();                 // the rest; rejects unknown --options
  bool help() { return flag("--help") || flag("-h"); }

 private:
  std::vector<std::string> a_;
};

long long to_count(const std::string& s, const char* what);            // accepts 1e6, 1000000
double to_real(const std::string& s, const char* what);                // a finite number
std::vector<double> to_reals(const std::string& s, const char* what);  // 1.5,2,3e-2

// --method incremental|digital and --grid SIDE (digital only) into opt's method and grid.
template <class Options>
void read_method(Args& a, Options& opt) {
  std::string method, grid;
  a.value("--method", method);
  a.value("--grid", grid);
  if (!method.empty()) opt.method = parse_method(method);
  if (!grid.empty()) {
    if (opt.method != Method::Digital) throw UsageError("--grid needs --method digital");
    opt.grid = to_count(grid, "--grid");
  }
}

class Timer {
 public:
  Timer(const Global& g, const char* phase)
      : g_(g), phase_(phase), t0_(std::chrono::steady_clock::now()) {}
  ~Timer() {
    if (!g_.verbose) return;
    double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
    std::fprintf(stderr, "[time] %-12s %10.2f ms\n", phase_, ms);
  }

 private:
  const Global& g_;
  const char* phase_;
  std::chrono::steady_clock::time_point t0_;
};

int cmd_gen(const Global& g, Args& a);
int cmd_check(const Global& g, Args& a);
int cmd_info(const Global& g, Args& a);
int cmd_edt(const Global& g, Args& a);
int cmd_cvd(const Global& g, Args& a);
int cmd_stipple(const Global& g, Args& a);
int cmd_delaunay2d(const Global& g, Args& a);
int cmd_cdt2d(const Global& g, Args& a);
int cmd_mesh2d(const Global& g, Args& a);
int cmd_hull3d(const Global& g, Args& a);
int cmd_delaunay3d(const Global& g, Args& a);
int cmd_cells(const Global& g, Args& a);

// A computation's phase times and counters on stderr (--verbose).
void print_stats(const RunStats& s);

// What the 3D mesh commands (hull3d, delaunay3d) share: one point file read as 3D points, -o
// MESH with one of `exts` (what: "for a hull", ...) and/or --check, the writers' options.
// hint follows the message for a 2D file.
struct PointsToMesh {
  std::string src, out, ext;  // ext: out's extension, "" when there is no -o
  bool check = false;
  io::WriteOptions wo;
  io::PointSet p;
};
PointsToMesh points_to_mesh(const Global& g, Args& a, const char* cmd,
                            const std::vector<std::string>& exts, const char* what,
                            const char* hint = "");

// The mesh writers' options --compress (.vtu) and --ascii (.vtu, .ply), checked against the
// output path `out` (UsageError where they do not apply).
io::WriteOptions mesh_write_options(Args& a, const std::string& out);

// A 2D triangle mesh as the writers take it: the coordinates and triangles (moved in), and the
// regions' attribute per triangle as cell data "attribute" when there is one (.vtu/.vtk carry
// it, .msh makes its integers the physical tags).
io::Mesh triangle_mesh2d(HostVector<double> coords, HostVector<std::int32_t> triangles,
                         const HostVector<double>& attribute);

}  // namespace gpugeom::cli
