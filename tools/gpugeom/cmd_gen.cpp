// gpugeom gen: seeded point sets of the thesis distributions.
#include <iostream>

#include "cli.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/io.hpp"

namespace gpugeom::cli {

int cmd_gen(const Global& g, Args& a) {
  if (a.help()) {
    std::cout << "usage: gpugeom gen DIST -n N -o FILE [--seed S] [--ascii]\n\n"
                 "DIST is a distribution name followed by 2d or 3d:\n  2d:";
    for (auto& d : distributions2d()) std::cout << " " << d << "2d";
    std::cout << "\n  3d:";
    for (auto& d : distributions3d()) std::cout << " " << d << "3d";
    std::cout
        << "\n\nFILE's extension picks the format: .ply (binary unless --ascii) .xyz .txt .csv\n"
           ".off .obj .node .npy. The points depend only on DIST, N and the seed (default 1).\n";
    return kOk;
  }
  std::string n_s, out, seed_s = "1";
  if (!a.value("-n", n_s)) throw UsageError("missing -n N (the number of points)");
  if (!a.value("-o", out) && !a.value("--output", out)) throw UsageError("missing -o FILE");
  a.value("--seed", seed_s);
  const bool ascii = a.flag("--ascii");
  auto pos = a.positionals();
  if (pos.size() != 1) throw UsageError("expected one distribution name, e.g. 'uniform3d'");
  const std::string dist = pos[0];
  if (dist.size() < 3 ||
      (dist.substr(dist.size() - 2) != "2d" && dist.substr(dist.size() - 2) != "3d"))
    throw UsageError("distribution '" + dist +
                     "' must end in 2d or 3d (e.g. uniform3d); see 'gpugeom gen --help'");
  const int dim = dist[dist.size() - 2] - '0';
  const std::string base = dist.substr(0, dist.size() - 2);
  const long long n = to_count(n_s, "-n");
  const unsigned long long seed = (unsigned long long)to_count(seed_s, "--seed");
  io::PointSet ps;
  ps.dim = dim;
  {
    Timer t(g, "generate");
    if (dim == 2) {
      auto p = generate2d(base, n, seed);
      ps.coords.assign(&p.data()->x, &p.data()->x + 2 * p.size());
    } else {
      auto p = generate3d(base, n, seed);
      ps.coords.assign(&p.data()->x, &p.data()->x + 3 * p.size());
    }
  }
  {
    Timer t(g, "write");
    io::WriteOptions o;
    o.binary = !ascii;
    io::write_points(out, ps, o);
  }
  if (!g.quiet) std::cout << "wrote " << n << " " << dist << " points to " << out << "\n";
  return kOk;
}

}  // namespace gpugeom::cli
