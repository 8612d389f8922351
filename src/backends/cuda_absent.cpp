// Linked instead of the CUDA backend when horizon is built without CUDA.
#include "backends.hpp"
#include "horizon/error.hpp"

namespace horizon::detail {

bool cuda_usable() { return false; }

NeighborList search_cuda(PointView, const SearchOptions&, SearchStats&) {
  throw Error("horizon was built without CUDA (configure with -DHORIZON_CUDA=on)");
}

}  // namespace horizon::detail
