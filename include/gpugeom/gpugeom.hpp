// Umbrella header: everything public in gpugeom.
#pragma once
#include "gpugeom/common.hpp"
#include "gpugeom/cvd.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/edt.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/grid_view.hpp"
#include "gpugeom/hull3d.hpp"
#include "gpugeom/io.hpp"
#include "gpugeom/locate.hpp"
#include "gpugeom/predicates.hpp"
#include "gpugeom/spatial.hpp"
