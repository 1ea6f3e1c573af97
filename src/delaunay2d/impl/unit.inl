// 2D Delaunay's algorithm, included inside an executor's namespace (NS::cpu_impl or NS::cuda_impl)
// after `Exec` and `edt_impl` are named there: the one list of its parts, in dependency order,
// for every translation unit that compiles it (the library's and the tests').
#include "delaunay2d/impl/geometry.inl"
#include "delaunay2d/impl/prepare.inl"
#include "delaunay2d/impl/mesh.inl"
#include "delaunay2d/impl/flip_round.inl"
#include "delaunay2d/impl/store.inl"
#include "delaunay2d/impl/triangulator.inl"
#include "delaunay2d/impl/start.inl"
#include "delaunay2d/impl/batch.inl"
#include "delaunay2d/impl/rounds.inl"
#include "delaunay2d/impl/finish.inl"
#include "delaunay2d/impl/triangulate.inl"
#include "delaunay2d/impl/dynamic.inl"
#include "edt/impl/point_voronoi.inl"
#include "delaunay2d/digital/impl/sketch.inl"
#include "delaunay2d/digital/impl/shift.inl"
#include "delaunay2d/digital/impl/pipeline.inl"
