/// @file
/// Several GPUs of one host without a cluster (issue 51): a call takes a list of devices and
/// splits the work by the blocks gpugeom.dask uses; one host thread and stream per device, each
/// part computed from host memory into its place in the host result.
#pragma once
#include <vector>

#include "gpugeom/edt.hpp"

namespace gpugeom {

/// distance_transform of a host grid of 3 to 8 axes (give a 2D grid as (rows, 1, columns)) on
/// several devices: the grid is split along C axis 0 into one slab per entry of `devices`
/// (CUDA ordinals; a device may be named twice, an empty list takes every device of the host),
/// each slab's first and last sites per column are found on host threads, then every slab is
/// transformed at once on its device with its columns' nearest sites outside it (EdtOptions::slab)
/// and its outputs go straight into their place in the whole grid's (into's arrays where given).
/// The result is exactly distance_transform's. opt.device and opt.stream are not read (each
/// device works on its host thread's default stream); opt.threads, where given, is the host
/// threads of all slabs together. With opt.backend == Backend::Cpu every entry is a slab on the
/// CPU executor (the same result; for machines without GPUs and for tests). Throws
/// Error(InvalidArgument) for labels (a slab cannot rank the whole grid's sites), slices or a
/// slab in opt, grids of fewer than 3 axes; otherwise as distance_transform.
EdtResult distance_transform_devices(const GridView& grid, SiteRule rule,
                                     const std::vector<int>& devices, const EdtOptions& opt = {});

}  // namespace gpugeom
