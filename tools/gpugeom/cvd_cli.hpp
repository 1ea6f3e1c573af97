// What `gpugeom cvd` and `gpugeom stipple` share: the Lloyd options, a progress line on the
// terminal, and list parsing.
#pragma once
#include <string>

#include "cli.hpp"
#include "gpugeom/cvd.hpp"

namespace gpugeom::cli {

// Reads --iterations --tolerance --energy-tolerance --supersample --seed into o.
void read_lloyd_options(Args& a, CvdOptions& o);
extern const char* const kLloydHelp;  // their --help lines

// A progress line on stderr, redrawn in place after each iteration (unless quiet).
void attach_progress(const Global& g, CvdOptions& o);
// Ends the progress line with a summary of the run.
void finish_progress(const Global& g, const CvdResult& r);

}  // namespace gpugeom::cli
