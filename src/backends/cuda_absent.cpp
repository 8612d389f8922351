// Linked instead of the CUDA backend when horizon is built without CUDA: every entry point
// exists and says why it cannot run.
#include "backends.hpp"
#include "../core/device_part.hpp"
#include "horizon/cuda.hpp"
#include "horizon/device_verlet_list.hpp"
#include "horizon/error.hpp"

namespace horizon {

namespace {
[[noreturn]] void no_cuda() {
  throw Error("horizon was built without CUDA (configure with -DHORIZON_CUDA=on)");
}
}  // namespace

namespace detail {
bool cuda_usable() { return false; }
NeighborList search_cuda(PointView, const SearchOptions&, SearchStats&) { no_cuda(); }
DevicePart search_local_part(const LocalPart&, const SearchOptions&, SearchStats*) { no_cuda(); }
Buffer<std::int64_t> host_offsets(const DevicePart&) { no_cuda(); }
void copy_part_rows(const std::vector<PartRows>&, const std::int64_t*, point_id*) { no_cuda(); }
}  // namespace detail

void DeviceNeighborList::Free::operator()(void*) const {}
NeighborList DeviceNeighborList::to_host(bool) const { no_cuda(); }
DeviceNeighborList search_device(const double*, std::size_t, int, const SearchOptions&, cuda_stream,
                                 SearchStats*) {
  no_cuda();
}
DeviceVerletList::DeviceVerletList(const double*, std::size_t, int, const SearchOptions&, double, cuda_stream) {
  no_cuda();
}
bool DeviceVerletList::needs_rebuild(const double*) const { no_cuda(); }
DeviceNeighborList DeviceVerletList::refresh(const double*) const { no_cuda(); }
void cuda_release_cached_memory(int) {}
int cuda_use_device_of(const void*) { no_cuda(); }
int cuda_device_count() { return 0; }
std::string cuda_device_name(int) { return ""; }

}  // namespace horizon
