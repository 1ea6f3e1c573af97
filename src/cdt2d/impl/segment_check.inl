// The device entries' check of segment indices, in the executor's memory; included inside the
// {cpu,cuda}_impl namespaces of cdt2d and refine2d (each translation unit its own copy of the
// lambda, as exec/tu_exec.hpp explains).

// Throws Error(InvalidInput) naming the first segment (of nseg pairs at segments) that names a
// point outside 0..n-1.
inline void check_segment_indices(Exec& ex, const std::int32_t* segments, std::int64_t nseg,
                                  std::int64_t n) {
  if (nseg <= 0) return;
  auto bad = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      2 * nseg,
      GG_LAMBDA(std::int64_t k)->std::int64_t {
        return segments[k] < 0 || segments[k] >= n ? k : INT64_MAX;
      },
      std::int64_t(INT64_MAX), thrust::minimum<std::int64_t>(), bad.data());
  std::int64_t k = INT64_MAX;
  ex.to_host(bad.data(), 1, &k);
  if (k == INT64_MAX) return;
  std::int32_t v = 0;
  ex.to_host(segments + k, 1, &v);
  throw Error(ErrorCode::InvalidInput, "segment " + std::to_string(k / 2) + " names point " +
                                           std::to_string(v) + ", outside 0.." +
                                           std::to_string(n - 1));
}
