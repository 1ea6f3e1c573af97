// The headers Delaunay refinement (impl/*.inl) needs: included, before the executor's own
// header, by each executor's unit (refine2d_cpu.cpp, refine2d_cuda.cu).
#pragma once
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "predicates/predicates.hpp"
#include "refine2d/quality.hpp"
#include "refine2d/refine2d_backend.hpp"
