// gpugeom: exact computational geometry on the GPU, from the command line.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <thread>

#include "cli.hpp"

namespace gpugeom::cli {

bool Args::flag(const std::string& name) {
  for (std::size_t i = 0; i < a_.size(); ++i)
    if (a_[i] == name) {
      a_.erase(a_.begin() + i);
      return true;
    }
  return false;
}

bool Args::value(const std::string& name, std::string& out) {
  for (std::size_t i = 0; i < a_.size(); ++i) {
    if (a_[i] == name) {
      if (i + 1 >= a_.size()) throw UsageError("option " + name + " needs a value");
      out = a_[i + 1];
      a_.erase(a_.begin() + i, a_.begin() + i + 2);
      return true;
    }
    if (a_[i].rfind(name + "=", 0) == 0) {
      out = a_[i].substr(name.size() + 1);
      a_.erase(a_.begin() + i);
      return true;
    }
  }
  return false;
}

void print_stats(const RunStats& s) {
  for (auto& ph : s.phase_ms)
    std::fprintf(stderr, "[phase] %-18s %10.2f ms\n", ph.first.c_str(), ph.second);
  for (auto& c : s.counter_map())
    std::fprintf(stderr, "[count] %-28s %lld\n", c.first.c_str(), (long long)c.second);
}

PointsToMesh points_to_mesh(const Global& g, Args& a, const char* cmd,
                            const std::vector<std::string>& exts, const char* what,
                            const char* hint) {
  PointsToMesh r;
  a.value("-o", r.out) || a.value("--output", r.out);
  r.check = a.flag("--check");
  r.wo = mesh_write_options(a, r.out);
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one point file (see --help)");
  if (r.out.empty() && !r.check) throw UsageError("nothing to do: give -o MESH or --check");
  r.ext = r.out.empty() ? "" : io::extension(r.out);
  if (!r.out.empty() && std::find(exts.begin(), exts.end(), r.ext) == exts.end()) {
    std::string list;
    for (std::size_t i = 0; i < exts.size(); ++i)
      list += (i == 0 ? "" : i + 1 == exts.size() ? " or " : ", ") + exts[i];
    throw UsageError("-o takes " + list + " " + what + " (got '" + r.out + "')");
  }
  r.src = pos[0];
  {
    Timer t(g, "read");
    r.p = io::read_points(r.src);
  }
  if (r.p.dim != 3)
    throw Error(ErrorCode::InvalidInput,
                r.src + " holds 2D points: " + cmd + " needs 3D points" + hint);
  return r;
}

io::WriteOptions mesh_write_options(Args& a, const std::string& out) {
  io::WriteOptions wo;
  wo.compress = a.flag("--compress");
  wo.binary = !a.flag("--ascii");
  if (wo.compress && !wo.binary) throw UsageError("--compress and --ascii exclude each other");
  if (wo.compress && (out.empty() || io::extension(out) != ".vtu"))
    throw UsageError("--compress applies to -o FILE.vtu only");
  return wo;
}

io::Mesh triangle_mesh2d(HostVector<double> coords, HostVector<std::int32_t> triangles,
                         const HostVector<double>& attribute) {
  io::Mesh mesh;
  mesh.dim = 2;
  mesh.cell_size = 3;
  mesh.coords = std::move(coords);
  mesh.cells = std::move(triangles);
  if (!attribute.empty())
    mesh.cell_data.push_back(io::make_data_array("attribute", io::ScalarType::F64, 1,
                                                 attribute.data(), attribute.size()));
  return mesh;
}

std::vector<std::string> Args::positionals() {
  for (auto& s : a_)
    if (s.size() > 1 && s[0] == '-' && !(s[1] >= '0' && s[1] <= '9'))
      throw UsageError("unknown option '" + s + "'");
  return a_;
}

long long to_count(const std::string& s, const char* what) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || v < 0 || v != double((long long)v))
    throw UsageError(std::string("expected a non-negative whole number for ") + what + ", got '" +
                     s + "'");
  return (long long)v;
}

double to_real(const std::string& s, const char* what) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || !std::isfinite(v))
    throw UsageError(std::string("expected a number for ") + what + ", got '" + s + "'");
  return v;
}

std::vector<double> to_reals(const std::string& s, const char* what) {
  std::vector<double> v;
  std::size_t at = 0;
  while (at <= s.size()) {
    const std::size_t c = std::min(s.find(',', at), s.size());
    v.push_back(to_real(s.substr(at, c - at), what));
    at = c + 1;
  }
  return v;
}
}  // namespace gpugeom::cli

using namespace gpugeom;
using namespace gpugeom::cli;

static const char* kUsageText =
    "usage: gpugeom [--backend auto|cpu|cuda] [--verbose] [--quiet] COMMAND [ARGS]\n"
    "\n"
    "commands:\n"
    "  gen DIST -n N -o FILE   generate a seeded point set (e.g. uniform3d, ball3d, circle2d)\n"
    "  check MESH [--points P] check a triangulation / Delaunay / convex hull exactly\n"
    "  info FILE | --device    summarise a point, mesh or grid file; or show the GPU\n"
    "  edt IN -o OUT.npy       exact distance transform / Voronoi diagram of an image or volume\n"
    "  cvd DENSITY -n N -o P   weighted centroidal Voronoi diagram (Lloyd) of a density\n"
    "  stipple IMG -o OUT.svg  stipple drawing of a photograph (also --png)\n"
    "  delaunay2d P -o MESH    exact 2D Delaunay triangulation (--voronoi, --draw, --check)\n"
    "  cdt2d IN.poly -o MESH   exact constrained Delaunay (segments, holes, regions; --check)\n"
    "  mesh2d IN.poly -q 30 -a 0.01 -o MESH   quality mesh of a domain (Triangle's -q -a)\n"
    "  hull3d P -o MESH        exact 3D convex hull (--check)\n"
    "  delaunay3d P -o MESH    exact 3D Delaunay tetrahedralisation (--check)\n"
    "  cells P --box B -o T    Voronoi cells of 3D particles in a box, bounded or periodic\n"
    "\n"
    "global options:\n"
    "  --backend B   executor: auto (CUDA if a GPU is usable, else CPU), cpu, cuda;\n"
    "                the environment variable GPUGEOM_BACKEND sets the default\n"
    "  --verbose     print phase timings on stderr\n"
    "  --quiet       print nothing but errors\n"
    "\n"
    "'gpugeom COMMAND --help' describes each command. Exit status: 0 success, 1 a check\n"
    "failed, 2 usage error, 3 bad input file, 4 internal or GPU error.\n";

static int run(int argc, char** argv) {
  Global g;
  std::vector<std::string> rest;
  std::string cmd;
  struct Joined {  // a thread joined on every way out of main
    std::thread t;
    const Global* g = nullptr;
    double ms = 0;  // its time (--verbose shows it: the part of a command's wall the read hides)
    ~Joined() {
      if (t.joinable()) t.join();
      if (g && g->verbose && ms > 0)
        std::fprintf(stderr, "[time] %-12s %10.2f ms (its own thread, beside the read)\n",
                     "gpu start", ms);
    }
  } warm;
  warm.g = &g;
  try {
    for (int i = 1; i < argc; ++i) {
      std::string s = argv[i];
      if (s == "--verbose" || s == "-v")
        g.verbose = true;
      else if (s == "--quiet" ||
               (s == "-q" && cmd != "mesh2d"))  // (mesh2d: -q is the angle, as Triangle's)
        g.quiet = true;
      else if (s == "--backend" && i + 1 < argc)
        g.backend = parse_backend(argv[++i]);
      else if (s.rfind("--backend=", 0) == 0)
        g.backend = parse_backend(s.substr(10));
      else if (s == "--backend")
        throw UsageError("option --backend needs a value");
      else if (cmd.empty() && (s == "--help" || s == "-h")) {
        std::cout << kUsageText;
        return kOk;
      } else if (cmd.empty() && s[0] != '-')
        cmd = s;
      else
        rest.push_back(s);
    }
    if (cmd.empty()) {
      std::cerr << kUsageText;
      return kUsage;
    }
    // The GPU's one-time start (its context, about 250 ms on the H100 machine) on another
    // thread while the command reads its input; joined before exit.
    const bool help = std::find(rest.begin(), rest.end(), "--help") != rest.end() ||
                      std::find(rest.begin(), rest.end(), "-h") != rest.end();
    if (g.backend != Backend::Cpu && !help &&
        (cmd == "delaunay2d" || cmd == "cdt2d" || cmd == "mesh2d" || cmd == "hull3d" ||
         cmd == "delaunay3d" || cmd == "edt" || cmd == "cvd" || cmd == "stipple" || cmd == "cells"))
      warm.t = std::thread([&warm] {
        const auto t0 = std::chrono::steady_clock::now();
        prepare_device();
        warm.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                      .count();
      });
    Args a(rest);
    if (cmd == "gen") return cmd_gen(g, a);
    if (cmd == "check") return cmd_check(g, a);
    if (cmd == "info") return cmd_info(g, a);
    if (cmd == "edt") return cmd_edt(g, a);
    if (cmd == "cvd") return cmd_cvd(g, a);
    if (cmd == "stipple") return cmd_stipple(g, a);
    if (cmd == "delaunay2d") return cmd_delaunay2d(g, a);
    if (cmd == "cdt2d") return cmd_cdt2d(g, a);
    if (cmd == "mesh2d") return cmd_mesh2d(g, a);
    if (cmd == "hull3d") return cmd_hull3d(g, a);
    if (cmd == "delaunay3d") return cmd_delaunay3d(g, a);
    if (cmd == "cells") return cmd_cells(g, a);
    throw UsageError("unknown command '" + cmd + "' (try 'gpugeom --help')");
  } catch (const UsageError& e) {
    std::cerr << "gpugeom" << (cmd.empty() ? "" : " " + cmd) << ": " << e.what() << "\n";
    return kUsage;
  } catch (const Error& e) {
    std::cerr << "gpugeom" << (cmd.empty() ? "" : " " + cmd) << ": " << error_code_name(e.code())
              << ": " << e.what() << "\n";
    switch (e.code()) {
      case ErrorCode::InvalidArgument:
        return kUsage;
      case ErrorCode::InvalidInput:
      case ErrorCode::DegenerateInput:
      case ErrorCode::Parse:
      case ErrorCode::Io:
        return kBadInput;
      default:
        return kInternal;
    }
  } catch (const std::bad_alloc&) {
    std::cerr << "gpugeom: out of host memory\n";
    return kInternal;
  } catch (const std::exception& e) {
    std::cerr << "gpugeom: internal error: " << e.what() << "\n";
    return kInternal;
  }
}

int main(int argc, char** argv) {
  const int code = run(argc, argv);
  // Every output is complete by now (the writers commit their files before returning, the
  // device thread is joined). The process ends here without static destructors: the CUDA
  // runtime's teardown of the device's context and pool is part of a command's wall time and
  // frees nothing the end of the process does not.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(code);
}
