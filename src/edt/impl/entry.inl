// The entry points edt_backend.hpp and edt_device.hpp declare, the same for both executors: a
// whole grid runs the passes compiled for the request's site packing (run.inl, included once
// for each in namespaces bits and linear), slices theirs by blocks (slices.inl, once for each
// block layout).

void run(const Request& req, Output& out, Stats& stats) {
  if (!req.slices.empty() && req.layout.columns)
    column_slices::run_slices(req, out, stats);
  else if (!req.slices.empty() && req.layout.linear)
    linear_slices::run_slices(req, out, stats);
  else if (!req.slices.empty())
    bits_slices::run_slices(req, out, stats);
  else if (req.layout.linear)
    linear::run_whole(req, out, stats);
  else
    bits::run_whole(req, out, stats);
}
// Modules built on the transform (cvd/) hold bit-packed sites (make_layout with
// Packing::Bits): their own code decodes them.
void feature_transform_held(Exec& ex, const Layout& L, const Metric& M, std::uint32_t* feat,
                            std::int64_t sites) {
  bits::feature_transform(ex, L, M, feat, nullptr, Tuning{}, sites, nullptr);
}
