// Input checks and the first tetrahedron: shared with delaunay3d (mesh/first_tetrahedron.hpp);
// included inside gpugeom::hull3d::{cpu,cuda}_impl after geometry.inl.

using mesh::collinear3;
using mesh::same_point;
using mesh::Tetra;
inline void throw_bad(std::int64_t bad) {
  mesh::throw_bad_coordinates(bad);
}
// The first tetrahedron with its fourth point below the plane of the first three.
inline Tetra first_tetrahedron(Exec& ex, const double* p, std::int64_t n, std::int64_t n_input) {
  return mesh::first_tetrahedron(ex, p, n, n_input, "a convex hull", false);
}
