// The headers weighted Lloyd iteration (impl/*.inl) needs: included, before the executor's own
// header, by each executor's unit (cvd_cpu.cpp, cvd_cuda.cu).
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <unordered_set>
#include <cuda/atomic>
#include <cstdint>
#include <thrust/functional.h>
#include <vector>

#include "base/clock.hpp"
#include "cvd/cvd_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/grid_input.hpp"
#include "exec/peak.hpp"
