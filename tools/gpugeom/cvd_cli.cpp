// Shared options and terminal progress of the CVD commands.
#include "cvd_cli.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace gpugeom::cli {

const char* const kLloydHelp =
    "  --iterations K        at most K Lloyd iterations (default 200)\n"
    "  --tolerance T         stop once no site moves more than T pixels (default 0.1)\n"
    "  --energy-tolerance E  also stop once the energy falls by less than the fraction E\n"
    "  --supersample S       Voronoi grid points per pixel along each axis (default 1): sites\n"
    "                        move in steps of 1/S pixel\n"
    "  --seed N              seed of the initial sites (default 1)\n";

void read_lloyd_options(Args& a, CvdOptions& o) {
  std::string v;
  if (a.value("--iterations", v)) o.max_iterations = int(to_count(v, "--iterations"));
  if (a.value("--tolerance", v)) o.move_tolerance = to_real(v, "--tolerance");
  if (a.value("--energy-tolerance", v)) o.energy_tolerance = to_real(v, "--energy-tolerance");
  if (a.value("--supersample", v)) o.supersample = int(to_count(v, "--supersample"));
  if (a.value("--seed", v)) o.seed = std::uint64_t(to_count(v, "--seed"));
}

void attach_progress(const Global& g, CvdOptions& o) {
  if (g.quiet) return;
  const int total = o.max_iterations;
  o.progress = [total](const CvdProgress& p) {
    const int width = 30, done = int(double(width) * p.iteration / total);
    char bar[64];
    for (int i = 0; i < width; ++i) bar[i] = i < done ? '#' : '.';
    bar[width] = 0;
    std::fprintf(stderr, "\r[%s] iteration %d/%d  moved %lld  max move %.2f px  energy %.6g   ",
                 bar, p.iteration, total, (long long)p.moved, p.max_move, p.energy);
    std::fflush(stderr);
    return true;
  };
}

void finish_progress(const Global& g, const CvdResult& r) {
  if (g.quiet) return;
  std::fprintf(stderr, "\n%s after %d iterations (%s, %.0f ms)\n",
               r.converged ? "converged" : "stopped", r.iterations, backend_name(r.stats.backend),
               r.stats.total_ms());
}

}  // namespace gpugeom::cli
