/// @file
/// Several GPUs of one host without a cluster (issue 51): a call takes a list of devices and
/// splits the work by the blocks gpugeom.dask uses; one host thread and stream per device, each
/// part computed from host memory, the parts put together into the host result.
#pragma once
#include <vector>

#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/delaunay3d.hpp"
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

/// delaunay3d of host points on several devices: the same Triangulation3d, array for array and byte
/// for byte (the tetrahedra, their order, neighbours, duplicates, vertex map and hull facets of a
/// single call). The points' bounding box is split into one block per entry of `devices` (CUDA
/// ordinals; a device may be named twice, an empty list takes every device of the host), by the
/// cells gpugeom.dask uses. Each block is triangulated on its device, on its own host thread, with
/// its own points, a ghost layer round them (4 mean point spacings) and the candidates for the
/// global hull's extreme points, and its stars are tested against all the points (blocks.hpp:
/// stars_final); a block whose stars are not all final is triangulated a second time with its own
/// points, the candidates and the points the other blocks' first triangulations name as its
/// borders, and is then exact without a test. Where the points lie on a convex surface (a sphere,
/// or a shell thinner than the spacing of a sample of 4096 of them: half the sample's points or
/// more are its hull's extreme points), the call is a single delaunay3d call on the first device:
/// every block would hold most of them. The owned tetrahedra (by their lowest vertex) and their
/// neighbours across blocks (matched by their faces) are put in delaunay3d's order by delaunay3d's
/// own output step, on the first listed device (or the CPU executor), which also prepares and
/// checks the points (docs/design-notes.md, "Several GPUs of one host"). A single entry is a single
/// delaunay3d call on that device. The points are split among the blocks on the first device, where
/// they were prepared, and each block gathers its points on its device from there (directly where
/// the GPUs have peer access; through the host where they do not). Each block's passes over its
/// simplices (owned rows, borders, face requests) run on its device, and its owned rows stay there
/// until the first device copies them; the finality test of the stars near a region's edge and the
/// face matching run on host threads. opt.device and opt.stream are not read; opt.threads, where
/// given, is the host threads of all blocks together; opt.into is written as delaunay3d writes it.
/// With opt.backend == Backend::Cpu every entry is a block on the CPU executor (the same result;
/// for machines without GPUs and for tests). The stats count the blocks, those that took a second
/// round and their local points, with the phases "blocks.*". Throws as delaunay3d (the points are
/// checked before any block runs), and Error(InvalidArgument) for Method::Digital or a negative
/// ordinal.
Triangulation3d delaunay3d_devices(const double* xyz, std::int64_t n,
                                   const std::vector<int>& devices,
                                   const Delaunay3dOptions& opt = {});

/// delaunay2d of host points on several devices, as delaunay3d_devices: the same
/// Triangulation2d, array for array, as a single call (a ghost layer of 6 mean spacings).
Triangulation2d delaunay2d_devices(const double* xy, std::int64_t n,
                                   const std::vector<int>& devices,
                                   const Delaunay2dOptions& opt = {});

}  // namespace gpugeom
