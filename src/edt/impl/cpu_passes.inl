// The CPU executor's versions of the whole-grid passes grid_transform.inl leaves to each
// backend; included by edt_cpu.cpp after it, once for each site packing.

// The CPU twin of the GPU's x pass: the general line pass, one thread walking each row.
void x_pass_rows(Exec& ex, const Layout& L, const Metric& M, const PassGeom& g,
                 const std::uint8_t* mask, const std::uint32_t* in, std::uint32_t* out,
                 std::uint32_t* scratch, std::int32_t* lo, std::int32_t* hi) {
  if (mask)
    init_features(ex, L, mask, out);
  else if (in != out)
    ex.copy(in, L.count(), out);
  line_pass(ex, L, M, g, out, scratch, lo, hi);
}
// The windowed pass's generic loop already walks a CPU thread's voxels in raster order.
bool window_pass_kernel(Exec&, const Layout&, int, std::int64_t, const std::uint32_t*,
                        std::uint32_t*, std::uint8_t*, bool) {
  return false;
}
