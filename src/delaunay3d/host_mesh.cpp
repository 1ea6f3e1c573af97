// Phase 2's partial copy of the tetrahedron store (tet.hpp): a hash table of the slots read
// so far, filled from the executor a star at a time.
#include <algorithm>
#include <string>

#include "delaunay3d/tet.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::del3d {

namespace {
std::size_t bucket(std::int32_t t, std::size_t mask) {
  return std::size_t((std::uint32_t(t) * 0x9e3779b1u) >> 7) & mask;
}
}  // namespace

void HostMesh::attach(SlotSource* src, std::int64_t used_slots) {
  src_ = src;
  used = used_slots;
  here_.assign(std::size_t(m) + 1, 0);
  rehash(1 << 16);
}

void HostMesh::rehash(std::size_t cap) {
  std::vector<std::int32_t> keys(cap, -1);
  std::vector<Tet> vals(cap);
  const std::size_t mask = cap - 1;
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    if (keys_[i] < 0) continue;
    std::size_t b = bucket(keys_[i], mask);
    while (keys[b] >= 0) b = (b + 1) & mask;
    keys[b] = keys_[i];
    vals[b] = vals_[i];
  }
  keys_.swap(keys);
  vals_.swap(vals);
}

const Tet* HostMesh::peek(std::int32_t t) const {
  if (all_) return t >= 0 && std::size_t(t) < dense_.size() ? &dense_[std::size_t(t)] : nullptr;
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t b = bucket(t, mask);; b = (b + 1) & mask) {
    if (keys_[b] == t) return &vals_[b];
    if (keys_[b] < 0) return nullptr;
  }
}

Tet* HostMesh::insert(std::int32_t t, const Tet& T) {
  if (2 * (n_ + 1) > keys_.size()) rehash(2 * keys_.size());
  const std::size_t mask = keys_.size() - 1;
  std::size_t b = bucket(t, mask);
  while (keys_[b] >= 0 && keys_[b] != t) b = (b + 1) & mask;
  if (keys_[b] < 0) {
    keys_[b] = t;
    ++n_;
  }
  vals_[b] = T;
  return &vals_[b];
}

Tet* HostMesh::slot(std::int32_t t) {
  if (t < 0 || t >= used)
    throw Error(ErrorCode::Internal, "internal error in star splaying: slot " + std::to_string(t) +
                                         " out of range; please report");
  if (const Tet* p = peek(t)) return const_cast<Tet*>(p);
  std::vector<Tet> T;
  src_->slots({t}, T);
  return insert(t, T[0]);
}

std::int32_t HostMesh::append(const Tet& T) {
  const std::int32_t t = std::int32_t(used++);
  if (all_)
    dense_.push_back(T);
  else
    insert(t, T);
  return t;
}

void HostMesh::load_stars(const std::vector<std::int32_t>& verts) {
  std::vector<std::int32_t> want;
  for (std::int32_t v : verts)
    if (v != m && !here_[std::size_t(v)]) want.push_back(v);
  std::sort(want.begin(), want.end());
  want.erase(std::unique(want.begin(), want.end()), want.end());
  if (want.empty() || all_) return;
  // (a star has about 27 tetrahedra, rarely fewer than 16: where the stars will not fit the
  // limit, walking them first would be wasted)
  const std::int64_t limit = used / 8 - std::int64_t(n_);
  std::vector<std::int32_t> slots;
  std::vector<Tet> tets;
  if (16 * std::int64_t(want.size()) > limit || !src_->stars(want, limit, slots, tets)) {
    load_all();
    return;
  }
  for (std::size_t i = 0; i < slots.size(); ++i)
    if (!peek(slots[i])) insert(slots[i], tets[i]);  // (what phase 2 changed stays)
  for (std::int32_t v : want) here_[std::size_t(v)] = 1;
}

void HostMesh::load_slots(const std::vector<std::int32_t>& slots) {
  if (all_) return;
  std::vector<std::int32_t> want;
  for (std::int32_t t : slots)
    if (t >= 0 && t < used && !peek(t)) want.push_back(t);
  std::sort(want.begin(), want.end());
  want.erase(std::unique(want.begin(), want.end()), want.end());
  if (want.empty()) return;
  std::vector<Tet> tets;
  src_->slots(want, tets);
  for (std::size_t i = 0; i < want.size(); ++i) insert(want[i], tets[i]);
}

void HostMesh::load_all() {
  if (all_) return;
  src_->all(dense_);  // (the slots appended here come after the store's)
  dense_.resize(std::size_t(used));
  for (std::size_t i = 0; i < keys_.size(); ++i)  // what phase 2 read or wrote stays
    if (keys_[i] >= 0) dense_[std::size_t(keys_[i])] = vals_[i];
  keys_.clear();
  vals_.clear();
  all_ = true;
  std::fill(here_.begin(), here_.end(), std::int8_t(1));
}

}  // namespace gpugeom::del3d
