// The members the three structures that follow their points (DynamicDelaunay2d,
// DynamicDelaunay3d, DynamicHull3d; issue 47) share, defined once (internal). Each public class
// keeps its own declarations and documentation, which say what a member means for its structure
// (a move repairs a triangulation, a hull is found again), so the classes do not share a base;
// they share this list of definitions, each a forward to the state (dynamic_state.hpp).
//
// GG_DYNAMIC_MEMBERS(CLS, NS, OPTIONS), in namespace gpugeom of the class's source, after a
// `refuse_options(const OPTIONS&)` there (the options the structure does not take): CLS::Impl
// (detail::DynamicImpl over the module's kept state), the constructors (host points, and
// from_device), the moves and destructor, insert, move and remove (host and executor memory), the
// counts every structure has, the backend, changes and stats. NS: the module's backend namespace
// (its entry table's make_kept, and check_count).
// GG_DYNAMIC_RESULTS(CLS, SIMPLICES, OTHER, KEPT_OTHER, HOST, HOST_FN, DEVICE, DEVICE_FN): the
// members whose names are the structure's: the simplex count SIMPLICES(), a second count
// OTHER() (the kept state's KEPT_OTHER()), and the results HOST HOST_FN() (host arrays) and
// DEVICE DEVICE_FN() (the executor's memory).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/dynamic_state.hpp"

namespace gpugeom::detail {

// The state behind a dynamic class (its Impl derives from this): DynamicState with the module's
// count check, and the stats put on a result.
template <class Kept>
struct DynamicImpl : DynamicState<Kept> {
  void (*check_count)(std::int64_t) = nullptr;  // the module's: refuses a total it cannot take
  void insert(const double* p, std::int64_t n, bool on_device) {
    DynamicState<Kept>::insert(p, n, on_device, check_count);
  }
  template <class Result>
  Result with_stats(Result r) const {
    r.stats = this->stats;
    return r;
  }
  // The structure as it stands, copied to host arrays, or to arrays in the executor's memory.
  template <class Result>
  Result host_result() const {
    Result r;
    this->kept->host_copy(r);
    return with_stats(std::move(r));
  }
  template <class Result>
  Result device_result() const {
    Result r;
    this->kept->device_copy(r);
    r.num_points = this->kept->points();
    r.backend = this->backend;
    return with_stats(std::move(r));
  }
};

// The options a dynamic structure does not take: Method::Digital where `same` is given (it names
// what Method::Incremental gives instead), and any of the `into` arrays (`readers` names the
// getters to read the results with).
template <class Options, class... Into>
void refuse_dynamic_options(const Options& opt, const char* cls, const char* same,
                            const char* readers, const Into&... into) {
  if (same && opt.method == Method::Digital)
    throw Error(ErrorCode::Unsupported, std::string(cls) +
                                            ": Method::Digital is not offered (Method::Incremental "
                                            "gives the same " +
                                            same + ")");
  if ((... || bool(into)))
    throw Error(ErrorCode::Unsupported,
                std::string(cls) + ": opt.into is not used; read the results with " + readers);
}

}  // namespace gpugeom::detail

// clang-format off
#define GG_DYNAMIC_MEMBERS(CLS, NS, OPTIONS)                                                      \
  struct CLS::Impl : ::gpugeom::detail::DynamicImpl<NS::Kept> {};                                 \
  namespace {                                                                                     \
  /* A state on backend b before its first points. (Impl is private: named by the members.) */  \
  template <class Impl>                                                                           \
  std::unique_ptr<Impl> start_state(const OPTIONS& opt, std::int64_t n, Backend b) {              \
    refuse_options(opt);                                                                          \
    NS::check_count(n);                                                                           \
    auto impl = std::make_unique<Impl>();                                                         \
    impl->backend = b;                                                                            \
    impl->check_count = &NS::check_count;                                                         \
    impl->kept = GG_ENTRIES(b, NS).make_kept(opt);                                                \
    return impl;                                                                                  \
  }                                                                                               \
  }                                                                                               \
  CLS::CLS(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}                                \
  CLS::CLS(const double* p, std::int64_t n, const OPTIONS& opt)                                   \
      : impl_(start_state<Impl>(opt, n, resolve_backend(opt.backend, opt.device))) {              \
    impl_->insert(p, n, false);                                                                   \
  }                                                                                               \
  CLS CLS::from_device(const double* device_p, std::int64_t n, const OPTIONS& opt) {              \
    auto impl = start_state<Impl>(                                                                \
        opt, n, device_entry_backend(opt.backend, opt.device, #CLS "::from_device"));             \
    impl->insert(device_p, n, true);                                                              \
    return CLS(std::move(impl));                                                                  \
  }                                                                                               \
  CLS::CLS(CLS&&) noexcept = default;                                                             \
  CLS& CLS::operator=(CLS&&) noexcept = default;                                                  \
  CLS::~CLS() = default;                                                                          \
  void CLS::insert(const double* p, std::int64_t n) { impl_->insert(p, n, false); }               \
  void CLS::insert_device(const double* device_p, std::int64_t n) {                               \
    impl_->insert(device_p, n, impl_->backend == Backend::Cuda);                                  \
  }                                                                                               \
  void CLS::move(const double* p, std::int64_t n) { impl_->move(p, n, false); }                   \
  void CLS::move_device(const double* device_p, std::int64_t n) {                                 \
    impl_->move(device_p, n, impl_->backend == Backend::Cuda);                                    \
  }                                                                                               \
  void CLS::remove(const std::int32_t* indices, std::int64_t count) {                             \
    impl_->remove(indices, count, false);                                                         \
  }                                                                                               \
  void CLS::remove_device(const std::int32_t* device_indices, std::int64_t count) {               \
    impl_->remove(device_indices, count, impl_->backend == Backend::Cuda);                        \
  }                                                                                               \
  std::int64_t CLS::num_points() const { return impl_->kept->points(); }                          \
  std::int64_t CLS::num_removed() const { return impl_->kept->removed(); }                        \
  Backend CLS::backend() const { return impl_->backend; }                                         \
  void CLS::track_changes(bool on) { impl_->kept->track_changes(on); }                            \
  SimplexChanges CLS::changes() const { return impl_->changes(#CLS); }                            \
  DeviceSimplexChanges CLS::device_changes() const { return impl_->device_changes(#CLS); }        \
  auto CLS::stats() const->const decltype(impl_->stats)& { return impl_->stats; }
#define GG_DYNAMIC_RESULTS(CLS, SIMPLICES, OTHER, KEPT_OTHER, HOST, HOST_FN, DEVICE, DEVICE_FN)   \
  std::int64_t CLS::SIMPLICES() const { return impl_->kept->simplices(); }                        \
  std::int64_t CLS::OTHER() const { return impl_->kept->KEPT_OTHER(); }                           \
  HOST CLS::HOST_FN() const { return impl_->host_result<HOST>(); }                                \
  DEVICE CLS::DEVICE_FN() const { return impl_->device_result<DEVICE>(); }
// clang-format on
