// 3D Delaunay's algorithm, included inside an executor's namespace (NS::cpu_impl or NS::cuda_impl)
// after `Exec` and `edt_impl` are named there: the one list of its parts, in dependency order,
// for every translation unit that compiles it (the library's and the tests').
#include "delaunay3d/impl/geometry.inl"
#include "delaunay3d/impl/link.inl"
#include "edt/impl/point_voronoi.inl"
#include "delaunay3d/digital/impl/working_sets.inl"
#include "delaunay3d/impl/stars.inl"
#include "delaunay3d/impl/splay_checks.inl"
#include "delaunay3d/impl/splay.inl"
#include "delaunay3d/impl/repair_stars.inl"
#include "delaunay3d/impl/repair.inl"
#include "delaunay3d/digital/impl/pipeline.inl"
#include "delaunay3d/impl/triangulate.inl"
#include "delaunay3d/impl/kept.inl"
#include "delaunay3d/impl/dynamic.inl"
