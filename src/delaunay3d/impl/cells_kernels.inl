// Voronoi cells of 3D points in a box, bounded or periodic (issue 49), on the executor. Included
// inside gpugeom::del3d::{cpu,cuda}_impl after voronoi.inl (its ridges give the neighbours); the
// steps' driver, voronoi_cells_impl, follows in cells.inl.
//
// 1. The points, checked, and along periodic axes taken modulo the box. Along those axes the
//    images of the points within a layer of width w outside the box are added (w starts at four
//    mean spacings).
// 2. Their Delaunay tetrahedralisation (delaunay3d_device on this executor) and its ridges
//    (vor3_ridge_lengths): per point, its Voronoi neighbours, exactly; edges that only cut a
//    cospherical cell have no ridge and give no plane.
// 3. Per point, on one thread: the box (padded by w along periodic axes) cut by the bisector
//    plane of each neighbour, nearest first (convex_cell.hpp), until the next plane lies beyond
//    every vertex; then measured, its faces (neighbour, area) written into room for as many
//    faces as it has planes. Periodic: a cell is only right if every point that could cut it is
//    there, that is if the ball round each of its vertices through the site lies within the
//    padded box; where one does not, w doubles and all is done again.
// 4. The faces gathered by scanned offsets; with the polygons asked for, every cell is built
//    again to write its vertices and its faces' vertex lists (building twice costs less than
//    keeping every cell's polyhedron).
//
// A thread keeps its cell in local arrays for 48 faces; a cell that outgrows them (a point
// inside a sphere of many others) is built again in executor memory with room for all its
// planes.

namespace vcells {

constexpr int kFaces = 48, kVertices = 96, kEntries = 288;

struct CellJob {
  const double* xyz;            // originals (taken into the box), then images
  const std::int32_t* src;      // per point, the original it is an image of (-1: a far point)
  const std::int32_t* dup;      // duplicate map of the originals (null: none)
  const std::int64_t* nb_from;  // n + 1: each original's neighbours in nb_key
  const std::uint64_t* nb_key;  // (original << 32 | neighbour), sorted
  const std::int64_t* nb_edge;  // per entry of nb_key, its ridge: 6 tetrahedron + edge
  const std::int32_t *tet, *tnb, *vid;  // the tetrahedralisation, each tetrahedron's class
  const double* cc;                     // per class, its circumcentre (the Voronoi vertex)
  std::int64_t nt;
  double plo[3], phi[3];  // the box, padded by w along periodic axes
  bool periodic[3];
  std::int64_t n;
  // measures, counts and faces (cell_count); cell i's faces at slot nb_from[i] + 6 i
  double *volume, *area, *centroid;
  std::int32_t *nfaces, *nverts, *nents;
  // 1: reaches past the images, 2: outgrew the room it was given, 3: to be cut from the box
  std::int8_t* flag;
  std::int8_t* how;  // 0: read from the diagram, 1: cut in a thread's room, 2: in executor memory
  std::int32_t* slot_plane;
  double* slot_area;
  // polygons (cell_write)
  const std::int64_t *vert_off, *ent_off, *face_off;
  double* vertices;
  std::int64_t* face_vert_off;
  std::int32_t* face_verts;
};

// The cell's planes are numbered 0..5 for the box's walls, 6 + k for its k-th neighbour.
GG_HD inline void cell_build(const CellJob& J, std::int64_t i, cells::ConvexCell& C) {
  using exact::sub_rn;
  const double* p = J.xyz + 3 * i;
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = sub_rn(J.plo[d], p[d]), hi[d] = sub_rn(J.phi[d], p[d]);
  C.box(lo, hi);
  const std::int64_t from = J.nb_from[i], k = J.nb_from[i + 1] - from;
  if (C.overflow) return;
  if (k + 7 > C.s.fcap) {  // (every neighbour may give a face: not enough room)
    C.overflow = true;
    return;
  }
  auto normal = [&](std::int64_t j, double* nrm) {
    const std::int64_t q = std::int64_t(J.nb_key[from + j] & 0xffffffffu);
    for (int d = 0; d < 3; ++d) nrm[d] = sub_rn(J.xyz[3 * q + d], p[d]);
  };
  // nearest first (insertion sort by squared distance, then by rank): the cell shrinks fast
  // and the cut can stop at the first plane beyond it
  for (std::int64_t j = 0; j < k; ++j) {
    double nrm[3];
    normal(j, nrm);
    const double key = cells::dot3(nrm, nrm);
    std::int64_t at = j;
    while (at > 0 && C.s.okey[at - 1] > key) {
      C.s.okey[at] = C.s.okey[at - 1], C.s.oidx[at] = C.s.oidx[at - 1];
      --at;
    }
    C.s.okey[at] = key, C.s.oidx[at] = std::int32_t(j);
  }
  for (std::int64_t j = 0; j < k && !C.overflow && !C.empty(); ++j) {
    double nrm[3];
    normal(C.s.oidx[j], nrm);
    if (C.beyond(nrm)) break;
    C.cut(nrm, C.s.okey[j] / 2, std::int32_t(6 + C.s.oidx[j]));
  }
}

GG_HD inline bool cell_skipped(const CellJob& J, std::int64_t i) {
  return J.dup && J.dup[i] >= 0 && J.dup[i] != std::int32_t(i);  // (a copy: its twin has it)
}

// The face of cell C with the smallest plane above `last` (a cell has a few dozen faces).
GG_HD inline int next_face(const cells::ConvexCell& C, std::int32_t last) {
  int f = -1;
  for (int g = 0; g < C.nf; ++g)
    if (C.s.fplane[g] > last && (f < 0 || C.s.fplane[g] < C.s.fplane[f])) f = g;
  return f;
}

// Builds and measures cell i, counts its faces, vertices and face-vertex entries, and writes
// its faces' planes and areas, in the order of their planes, into its slots.
GG_HD inline void cell_count(const CellJob& J, std::int64_t i, cells::ConvexCell& C) {
  using exact::add_rn;
  using exact::sub_rn;
  J.flag[i] = 0;
  J.volume[i] = J.area[i] = 0;
  J.nfaces[i] = J.nverts[i] = J.nents[i] = 0;
  const double* p = J.xyz + 3 * i;
  for (int d = 0; d < 3; ++d) J.centroid[3 * i + d] = p[d];
  if (cell_skipped(J, i)) return;
  cell_build(J, i, C);
  if (C.overflow) {
    J.flag[i] = 2;
    return;
  }
  double cen[3];
  J.volume[i] = C.measure(cen);
  for (int d = 0; d < 3; ++d) J.centroid[3 * i + d] = add_rn(p[d], cen[d]);
  double area = 0;
  std::int32_t ents = 0, last = -1;
  const std::int64_t slot = J.nb_from[i] + 6 * i;
  for (int j = 0; j < C.nf; ++j) {
    const int f = next_face(C, last);
    last = C.s.fplane[f];
    const double a = C.face_area(f);
    J.slot_plane[slot + j] = last, J.slot_area[slot + j] = a;
    area = add_rn(area, a);
    ents += C.s.flen[f];
  }
  J.area[i] = area;
  J.nfaces[i] = C.nf, J.nverts[i] = C.nv, J.nents[i] = ents;
  for (int k = 0; k < C.nv; ++k) {  // (periodic: every point that could cut the cell is there?)
    const double* v = C.vertex(k);
    const double r = sqrt(cells::dot3(v, v));
    for (int d = 0; d < 3; ++d) {
      if (!J.periodic[d]) continue;
      const double at = add_rn(p[d], v[d]);
      if (sub_rn(at, r) < J.plo[d] || add_rn(at, r) > J.phi[d]) J.flag[i] = 1;
    }
  }
}

// Builds cell i again and writes its vertices and its faces' vertex lists (faces in the order
// of their planes, as cell_count wrote them) where the scanned offsets put them.
GG_HD inline void cell_write(const CellJob& J, std::int64_t i, cells::ConvexCell& C) {
  using exact::add_rn;
  if (cell_skipped(J, i)) return;
  cell_build(J, i, C);
  if (C.overflow) return;  // (cannot happen: the same room as when it was counted)
  const double* p = J.xyz + 3 * i;
  const std::int64_t v0 = J.vert_off[i];
  for (int k = 0; k < C.nv; ++k)
    for (int d = 0; d < 3; ++d) J.vertices[3 * (v0 + k) + d] = add_rn(p[d], C.vertex(k)[d]);
  const std::int32_t* e = C.faces_ent();
  std::int64_t at = J.ent_off[i];
  std::int32_t last = -1;
  for (int j = 0; j < C.nf; ++j) {
    const int f = next_face(C, last);
    last = C.s.fplane[f];
    J.face_vert_off[J.face_off[i] + j] = at;
    const std::int32_t* r = e + C.s.fstart[f];
    for (int k = 0; k < C.s.flen[f]; ++k) J.face_verts[at++] = std::int32_t(v0 + r[k]);
  }
}

// A cell read from the diagram (no wall cuts it): its faces are its ridges, each the ring of
// circumcentres round a Delaunay edge, and its volume the pyramids from the point over them.
// Returns false where the cell must be cut from the box instead: a vertex lies outside the box
// along an axis that does not wrap, or a ring or the cell outgrows the room here.
constexpr int kRing = 32;

struct Face {  // one ridge of a cell, relative to the site
  std::int32_t ring[kRing];
  int m = 0;
  bool reversed = false;  // (its ring runs clockwise seen from the neighbour)
  double area = 0, centroid[3] = {0, 0, 0};
};

GG_HD inline bool read_face(const CellJob& J, std::int64_t i, std::int64_t entry, Face& F) {
  using exact::add_rn;
  using exact::mul_rn;
  using exact::sub_rn;
  const std::int64_t c = J.nb_edge[entry];
  const Ring R = vor3_ring(J.tet, J.tnb, c / 6, int(c % 6), J.nt);
  if (!R.closed) return false;  // (an unbounded cell: only the far points have them)
  mesh::ClassRun run{};
  int m = 0;
  vor3_walk(J.tet, J.tnb, R, J.nt, [&](std::int64_t t) {
    const std::int32_t k = J.vid[t];
    if (run.step(k)) {
      if (m < kRing) F.ring[m] = k;
      ++m;
    }
  });
  m = int(run.length(true));
  if (m > kRing || m < 3) return false;
  F.m = m;
  const double* p = J.xyz + 3 * i;
  const std::int64_t q = std::int64_t(J.nb_key[entry] & 0xffffffffu);
  double v0[3], a[3] = {0, 0, 0}, g[3] = {0, 0, 0};
  for (int d = 0; d < 3; ++d) v0[d] = sub_rn(J.cc[3 * F.ring[0] + d], p[d]);
  double prev[3];
  for (int d = 0; d < 3; ++d) prev[d] = sub_rn(sub_rn(J.cc[3 * F.ring[1] + d], p[d]), v0[d]);
  double tri[kRing][3];  // (each fan triangle's doubled area vector)
  for (int k = 2; k < m; ++k) {
    double cur[3];
    for (int d = 0; d < 3; ++d) cur[d] = sub_rn(sub_rn(J.cc[3 * F.ring[k] + d], p[d]), v0[d]);
    cells::cross3(prev, cur, tri[k]);
    for (int d = 0; d < 3; ++d) a[d] = add_rn(a[d], tri[k][d]);
    for (int d = 0; d < 3; ++d) prev[d] = cur[d];
  }
  double nrm[3];
  for (int d = 0; d < 3; ++d) nrm[d] = sub_rn(J.xyz[3 * q + d], p[d]);
  F.reversed = cells::dot3(a, nrm) < 0;
  const double aa = cells::dot3(a, a);
  F.area = sqrt(aa) / 2;
  // the face's centroid: its fan triangles' centroids weighted by their areas (projected on a)
  double wsum = 0;
  for (int d = 0; d < 3; ++d) prev[d] = sub_rn(sub_rn(J.cc[3 * F.ring[1] + d], p[d]), v0[d]);
  for (int k = 2; k < m; ++k) {
    double cur[3];
    for (int d = 0; d < 3; ++d) cur[d] = sub_rn(sub_rn(J.cc[3 * F.ring[k] + d], p[d]), v0[d]);
    const double w = cells::dot3(tri[k], a);
    wsum = add_rn(wsum, w);
    for (int d = 0; d < 3; ++d) g[d] = add_rn(g[d], mul_rn(w, add_rn(prev[d], cur[d])));
    for (int d = 0; d < 3; ++d) prev[d] = cur[d];
  }
  for (int d = 0; d < 3; ++d) F.centroid[d] = add_rn(v0[d], wsum > 0 ? g[d] / (3 * wsum) : 0);
  return true;
}

// Measures and counts cell i from the diagram, as cell_count does from the box; how[i] = 1
// (and nothing written) where it must be cut instead.
GG_HD inline void cell_direct_count(const CellJob& J, std::int64_t i) {
  using exact::add_rn;
  using exact::mul_rn;
  using exact::sub_rn;
  J.flag[i] = 0;
  J.how[i] = 0;
  J.volume[i] = J.area[i] = 0;
  J.nfaces[i] = J.nverts[i] = J.nents[i] = 0;
  const double* p = J.xyz + 3 * i;
  for (int d = 0; d < 3; ++d) J.centroid[3 * i + d] = p[d];
  if (cell_skipped(J, i)) return;
  const std::int64_t from = J.nb_from[i], k = J.nb_from[i + 1] - from;
  std::int32_t seen[kVertices];  // (the cell's vertices, to count them)
  int nseen = 0;
  double vol = 0, area = 0, m[3] = {0, 0, 0};
  std::int32_t ents = 0;
  bool reach = false;
  const std::int64_t slot = from + 6 * i;
  for (std::int64_t j = 0; j < k; ++j) {
    Face F;
    if (!read_face(J, i, from + j, F)) {
      J.how[i] = 1;
      return;
    }
    for (int r = 0; r < F.m; ++r) {
      const std::int32_t v = F.ring[r];
      bool known = false;
      for (int s = 0; s < nseen && !known; ++s) known = seen[s] == v;
      if (known) continue;
      if (nseen == kVertices) {
        J.how[i] = 1;
        return;
      }
      seen[nseen++] = v;
      const double* x = J.cc + 3 * v;
      double rel[3];
      for (int d = 0; d < 3; ++d) rel[d] = sub_rn(x[d], p[d]);
      const double rad = sqrt(cells::dot3(rel, rel));
      for (int d = 0; d < 3; ++d) {
        if (!J.periodic[d]) {
          if (x[d] < J.plo[d] || x[d] > J.phi[d]) {  // (a wall cuts the cell)
            J.how[i] = 1;
            return;
          }
        } else if (sub_rn(x[d], rad) < J.plo[d] || add_rn(x[d], rad) > J.phi[d]) {
          reach = true;
        }
      }
    }
    const std::int64_t q = std::int64_t(J.nb_key[from + j] & 0xffffffffu);
    double nrm[3];
    for (int d = 0; d < 3; ++d) nrm[d] = sub_rn(J.xyz[3 * q + d], p[d]);
    const double pv = F.area * sqrt(cells::dot3(nrm, nrm)) / 6;  // (the pyramid's volume)
    vol = add_rn(vol, pv);
    for (int d = 0; d < 3; ++d) m[d] = add_rn(m[d], mul_rn(pv, F.centroid[d]));
    area = add_rn(area, F.area);
    ents += F.m;
    J.slot_plane[slot + j] = std::int32_t(6 + j), J.slot_area[slot + j] = F.area;
  }
  J.volume[i] = vol;
  J.area[i] = area;
  for (int d = 0; d < 3; ++d)  // (a pyramid's centroid: 3/4 of the way to its base's)
    J.centroid[3 * i + d] = add_rn(p[d], vol > 0 ? mul_rn(0.75, m[d]) / vol : 0);
  J.nfaces[i] = std::int32_t(k), J.nverts[i] = nseen, J.nents[i] = ents;
  if (reach) J.flag[i] = 1;
}

// Writes cell i's vertices and faces' vertex lists from the diagram (a cell cell_direct_count
// measured).
GG_HD inline void cell_direct_write(const CellJob& J, std::int64_t i) {
  if (cell_skipped(J, i)) return;
  const std::int64_t from = J.nb_from[i], k = J.nb_from[i + 1] - from;
  const std::int64_t v0 = J.vert_off[i];
  std::int32_t seen[kVertices];
  int nseen = 0;
  std::int64_t at = J.ent_off[i];
  for (std::int64_t j = 0; j < k; ++j) {
    Face F;
    read_face(J, i, from + j, F);
    J.face_vert_off[J.face_off[i] + j] = at;
    for (int r = 0; r < F.m; ++r) {
      const std::int32_t v = F.ring[F.reversed ? F.m - 1 - r : r];
      int s = 0;
      while (s < nseen && seen[s] != v) ++s;
      if (s == nseen) {
        seen[nseen++] = v;
        for (int d = 0; d < 3; ++d) J.vertices[3 * (v0 + s) + d] = J.cc[3 * v + d];
      }
      J.face_verts[at++] = std::int32_t(v0 + s);
    }
  }
}

// A cell's room: a thread's local arrays, or a slice of executor memory for the cells that
// outgrow them.
struct Room {
  int faces, vertices, entries;
  GG_HD std::int64_t doubles() const { return 3 * std::int64_t(vertices) + faces; }
  GG_HD std::int64_t ints() const {
    return 2 * std::int64_t(entries) + 4 * faces + 3 * std::int64_t(vertices);
  }
  GG_HD cells::CellStore store(double* x, std::int32_t* ints, std::int8_t* side) const {
    std::int32_t* e = ints;
    std::int32_t* f = e + 2 * entries;
    std::int32_t* v = f + 4 * faces;
    return cells::CellStore{x,
                            e,
                            f,
                            f + faces,
                            f + 2 * faces,
                            side,
                            v,
                            v + vertices,
                            v + 2 * vertices,
                            x + 3 * vertices,
                            f + 3 * faces,
                            vertices,
                            entries,
                            faces};
  }
};

// Runs cell_count (or cell_write) over the cells that outgrew a thread's room, chunk by chunk,
// each in its slice of executor memory with room for all its planes.
inline void over_big(Exec& ex, const CellJob& J, const std::int32_t* big, std::int64_t nbig,
                     const Room& room, std::int64_t chunk, bool write) {
  if (!nbig) return;
  auto d_x = ex.template alloc<double>(std::size_t(chunk * room.doubles()));
  auto d_i = ex.template alloc<std::int32_t>(std::size_t(chunk * room.ints()));
  auto d_s = ex.template alloc<std::int8_t>(std::size_t(chunk * room.vertices));
  double* bx = d_x.data();
  std::int32_t* bi = d_i.data();
  std::int8_t* bs = d_s.data();
  for (std::int64_t b = 0; b < nbig; b += chunk) {
    ex.for_each_index(
        std::min(chunk, nbig - b), GG_LAMBDA(std::int64_t j) {
          cells::ConvexCell C{
              room.store(bx + j * room.doubles(), bi + j * room.ints(), bs + j * room.vertices)};
          if (write)
            cell_write(J, big[b + j], C);
          else
            cell_count(J, big[b + j], C);
        });
  }
}

}  // namespace vcells
