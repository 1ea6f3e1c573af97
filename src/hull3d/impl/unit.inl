// The 3D hull's algorithm, included inside an executor's namespace (hull3d::cpu_impl or
// hull3d::cuda_impl) after `Exec` is named there: the one list of its parts, in dependency order.
#include "hull3d/impl/geometry.inl"
#include "hull3d/impl/prepare.inl"
#include "hull3d/impl/surface.inl"
#include "hull3d/impl/construct.inl"
#include "hull3d/impl/flipflop.inl"
#include "hull3d/impl/one_by_one.inl"
#include "hull3d/impl/hull.inl"
#include "hull3d/digital/impl/digital.inl"
#include "hull3d/impl/dynamic.inl"
