// The problems the benchmark driver can time, per backend. Each returns phase times in ms
// (median over repetitions after a warm-up): "upload", "compute", "download".
#pragma once
#include <map>
#include <string>
#include <vector>

namespace gpugeom::bench {

using Phases = std::map<std::string, double>;

struct ProblemInput {
  std::string problem;  // hilbert, orient3d, insphere
  int dim = 3;
  std::vector<double> coords;  // dim per point
  int reps = 5;
};

namespace cpu_impl {
Phases run(const ProblemInput& in);
}
namespace cuda_impl {
Phases run(const ProblemInput& in);
}

}  // namespace gpugeom::bench
