// The CPU executor's answer to pba.inl's line_pass_tiled; included by edt_cpu.cpp after
// pba.inl, once per site packing.

// Tiles in on-chip memory are a GPU device: a CPU thread's cache already holds its line.
bool line_pass_tiled(Exec&, const Layout&, const Metric&, int, std::int64_t, int, std::uint32_t*,
                     std::uint32_t*, const std::uint8_t*) {
  return false;
}
