// Hilbert sort on one executor; included inside gpugeom::cpu_impl / gpugeom::cuda_impl.
// pts: n points of D doubles (executor memory); order: n indices, written in curve order.
template <int D>
void hilbert_sort(Exec& ex, const double* pts, std::int64_t n, std::int32_t* order,
                  const spatial::Box& box) {
  auto keys = ex.template alloc<std::uint64_t>(std::size_t(n));
  std::uint64_t* k = keys.data();
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        k[i] = spatial::hilbert_key<D>(pts + i * D, box);
        order[i] = std::int32_t(i);
      });
  ex.sort_by_key(k, order, n);
  ex.sync();
}
