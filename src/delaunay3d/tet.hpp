// The tetrahedron store of delaunay3d, shared by the executors' phase 1 and the host's star
// splaying (internal).
#pragma once
#include <cstdint>
#include <vector>

namespace gpugeom::del3d {

// One slot: four vertices (a positively oriented tetrahedron; index m is the infinity point)
// and the four neighbours (mesh/adjacency.hpp's encoding: the tetrahedron across the face
// opposite vertex k). A dead slot has v[0] = -1. 32 bytes: one memory sector per read.
struct alignas(32) Tet {
  std::int32_t v[4];
  std::int32_t n[4];
};

// Where phase 2 reads slots it does not hold yet (the executor's store).
class SlotSource {
 public:
  virtual ~SlotSource() = default;
  // Every slot holding one of verts (their stars; a slot may come more than once), with its
  // tetrahedron. Returns false, fetching nothing, if a star is too large to gather or the
  // stars hold more than limit slots (the caller then takes all).
  virtual bool stars(const std::vector<std::int32_t>& verts, std::int64_t limit,
                     std::vector<std::int32_t>& slots, std::vector<Tet>& tets) = 0;
  virtual void slots(const std::vector<std::int32_t>& slots, std::vector<Tet>& tets) = 0;
  virtual void all(std::vector<Tet>& tets) = 0;  // every slot in use
};

// What phase 2 works on: the extended tetrahedralisation after phase 1, on the host, as far as
// phase 2 has read it: slots are fetched from the executor on first use, whole stars at a
// time, so that the cost follows the failed vertices' neighbourhoods and not the store's size;
// once that would be more than an eighth of the store, it takes the whole store in one copy
// (a plain array then: hashing millions of slots costs more than the copy).
// (Not thread-safe: parallel readers use peek on what was loaded before.)
class HostMesh {
 public:
  const double* pts = nullptr;        // m points, 3 each, curve order (host memory)
  std::int32_t m = 0;                 // the infinity vertex
  double s[3] = {0, 0, 0};            // the kernel point
  std::vector<std::int32_t> vt;       // a slot holding each vertex (m + 1 entries)
  std::vector<std::int32_t> written;  // slots phase 2 rewrote (only these go back up)
  std::int64_t used = 0;              // slots in the store (new ones are appended)

  void attach(SlotSource* src, std::int64_t used_slots);
  const Tet& get(std::int32_t t) { return *slot(t); }
  Tet& set(std::int32_t t) { return *slot(t); }             // (the caller also lists t in written)
  const Tet* peek(std::int32_t t) const;                    // nullptr if not loaded
  std::int32_t append(const Tet& T);                        // a new slot at the end
  void load_stars(const std::vector<std::int32_t>& verts);  // those not loaded yet
  void load_slots(const std::vector<std::int32_t>& slots);  // in one copy, those missing
  void load_all();
  std::int64_t loaded() const { return all_ ? std::int64_t(dense_.size()) : std::int64_t(n_); }

 private:
  Tet* slot(std::int32_t t);
  Tet* insert(std::int32_t t, const Tet& T);
  void rehash(std::size_t cap);
  // Open addressing, slot numbers as keys (-1: empty).
  std::vector<std::int32_t> keys_;
  std::vector<Tet> vals_;
  std::size_t n_ = 0;
  std::vector<std::int8_t> here_;  // per vertex: its whole star is loaded
  std::vector<Tet> dense_;         // every slot, once load_all ran
  bool all_ = false;
  SlotSource* src_ = nullptr;
};

struct SplayStats {
  std::int64_t failed_vertices = 0;     // vertices on a face that is not locally Delaunay
  std::int64_t stars_rebuilt = 0;       // made convex by Flip-Flop
  std::int64_t stars_touched = 0;       // every star that changed, those included
  std::int64_t insertions = 0;          // vertices inserted into stars while splaying
  std::int64_t rounds = 0;              // splaying rounds (each checks its items in parallel)
  std::int64_t removed = 0, added = 0;  // tetrahedra patched
  std::int64_t flat_added = 0;          // flat tetrahedra among the added ones (see peel_flat)
  std::int64_t us_stars = 0, us_queue = 0, us_patch = 0;  // time: rebuilding, splaying, patching
  std::int64_t us_load = 0;  // of which loading stars from the executor
};

// Adaptive star splaying (thesis 5.3.2): faces lists the faces that are not locally Delaunay
// (three vertices each), whose vertices it starts from; where that list is empty, failed[v] != 0
// marks them instead (and their stars are tested whole). Up to `threads` host threads (0: the
// OpenMP default) rebuild the failed stars and compute the patch.
// Rewrites the store (through mesh) into the Delaunay tetrahedralisation (slots of removed
// tetrahedra are reused or left dead; new ones may be appended; every slot it writes is added
// to mesh.written). Reads stars from mesh.vt, which must hold a live slot of every vertex; its
// cost follows the failed vertices' neighbourhoods (mesh loads what it reads). Throws
// Error(Internal) when a step that cannot fail on a valid input fails.
SplayStats splay(HostMesh& mesh, const std::vector<std::int8_t>& failed,
                 const std::vector<std::int32_t>& faces, int threads);

// Flat tetrahedra: four points exactly on one plane that the perturbation orders positively.
// They can only lie on the hull, in layers over the planes of hull facets with many points;
// all of them go to the outside at once, the faces between them and the tetrahedra of positive
// volume becoming hull facets, which leaves every other tetrahedron as it was: the result is
// still Delaunay, and the hull facets cover the same planes. `flats` lists the flat slots phase
// 1 left (the slots phase 2 wrote are looked at too), or all_slots says the list did not fit
// and every slot is looked at. Returns how many went.
std::int64_t peel_flat(HostMesh& mesh, const std::vector<std::int32_t>& flats, bool all_slots);

}  // namespace gpugeom::del3d
