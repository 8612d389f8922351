// The C API (include/horizon/horizon.h): thin wrappers that turn the C++ library's exceptions into
// status codes and a thread-local message, so that no exception crosses the C boundary.
#include "horizon/horizon.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "horizon/block_filter.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/cuda.hpp"
#include "horizon/error.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"
#include "horizon/verlet_list.hpp"
#include "horizon/version.hpp"

struct horizon_list {
  horizon::NeighborList list;
  double reach = 0;         // the longest bond the search could give (filter_bonds skips far rows)
  bool of_queries = false;  // ids index another point set: the filters do not apply
  bool one_based = false;
};

struct horizon_device_list {
  horizon::DeviceNeighborList list;
};

struct horizon_verlet {
  horizon::VerletList verlet;
  std::size_t points;
  int dims;
};

namespace {

thread_local std::string last_error;

/// A failure the wrappers detect themselves, with its status.
struct Refused {
  horizon_status status;
  std::string what;
};

[[noreturn]] void refuse(const std::string& what, horizon_status status = HORIZON_INVALID_INPUT) {
  throw Refused{status, what};
}

/// Runs `call`, turning every exception into a status and the thread's message.
template <typename Call>
horizon_status guarded(Call&& call) noexcept {
  try {
    call();
    last_error.clear();
    return HORIZON_OK;
  } catch (const Refused& e) {
    last_error = e.what;
    return e.status;
  } catch (const horizon::DeviceOutOfMemory& e) {
    last_error = e.what();
    return HORIZON_DEVICE_OUT_OF_MEMORY;
  } catch (const horizon::ListTooLarge& e) {
    last_error = e.what();
    return HORIZON_LIST_TOO_LARGE;
  } catch (const horizon::Error& e) {
    last_error = e.what();
    return HORIZON_INVALID_INPUT;
  } catch (const std::bad_alloc&) {
    last_error = "out of memory";
    return HORIZON_OUT_OF_MEMORY;
  } catch (const std::exception& e) {
    last_error = std::string("internal error: ") + e.what();
    return HORIZON_INTERNAL_ERROR;
  } catch (...) {
    last_error = "internal error: unknown exception";
    return HORIZON_INTERNAL_ERROR;
  }
}

void require(const void* pointer, const char* name) {
  if (pointer == nullptr) refuse(std::string(name) + " is NULL");
}

void require_points(const double* points, std::size_t n, int dims, const char* name) {
  if (dims != 2 && dims != 3) refuse(std::string(name) + ": dims is " + std::to_string(dims) + ", expected 2 or 3");
  if (n > 0) require(points, name);
}

/// The caller's options, of whatever size its header version had, as SearchOptions.
horizon::SearchOptions search_options(const horizon_options* given) {
  require(given, "options");
  horizon_options options;
  horizon_options_default(&options);
  if (given->size < offsetof(horizon_options, metric))
    refuse("options.size is " + std::to_string(given->size) + ": fill the options with horizon_options_default()");
  std::memcpy(&options, given, std::min(given->size, sizeof options));
  horizon::SearchOptions search;
  search.horizon = options.horizon;
  if (options.metric < HORIZON_METRIC_L2 || options.metric > HORIZON_METRIC_LINF)
    refuse("options.metric is " + std::to_string(options.metric) + ": expected HORIZON_METRIC_L2, _L1 or _LINF");
  search.metric = options.metric == HORIZON_METRIC_L2   ? horizon::Metric::euclidean
                  : options.metric == HORIZON_METRIC_L1 ? horizon::Metric::manhattan
                                                        : horizon::Metric::chebyshev;
  search.cells_per_horizon = options.cells_per_horizon;
  search.half = options.half != 0;
  search.sort_rows = options.sort_rows != 0;
  if (options.backend < HORIZON_BACKEND_AUTO || options.backend > HORIZON_BACKEND_CUDA)
    refuse("options.backend is " + std::to_string(options.backend) + ": expected HORIZON_BACKEND_AUTO, _SERIAL, _OPENMP or _CUDA");
  search.backend = static_cast<horizon::Backend>(options.backend);  // the same order
  if (!horizon::backend_available(search.backend))
    refuse(std::string("backend '") + horizon::backend_name(search.backend) + "' is not available here",
           HORIZON_BACKEND_UNAVAILABLE);
  if (options.threads < 0) refuse("options.threads is " + std::to_string(options.threads) + ": expected 0 (all cores) or more");
  search.threads = options.threads;
  search.device = options.device;
  for (int a = 0; a < 3; ++a) search.box[a] = options.box[a];
  search.max_memory = options.max_memory;
  search.gpu_max_memory = options.gpu_max_memory;
  return search;
}

horizon_list* new_list(horizon::NeighborList list, double reach, bool of_queries) {
  return new horizon_list{std::move(list), reach, of_queries, false};
}

double largest(const double* values, std::size_t n) {
  double most = 0;
  for (std::size_t i = 0; i < n; ++i) most = values[i] > most ? values[i] : most;
  return most;
}

void require_filterable(const horizon_list* list) {
  require(list, "list");
  if (list->of_queries) refuse("the list is of query points against references: filter lists of one point set");
  if (list->one_based) refuse("the list was made one-based: filter it before horizon_list_make_one_based()");
}

}  // namespace

extern "C" {

const char* horizon_version(void) { return horizon::version(); }

const char* horizon_last_error(void) { return last_error.c_str(); }

void horizon_options_default(horizon_options* options) {
  if (options == nullptr) return;
  *options = horizon_options{};
  options->size = sizeof(horizon_options);
  options->metric = HORIZON_METRIC_L2;
  options->cells_per_horizon = 1;
  options->sort_rows = 1;
  options->backend = HORIZON_BACKEND_AUTO;
}

int horizon_backend_available(horizon_backend backend) {
  if (backend < HORIZON_BACKEND_AUTO || backend > HORIZON_BACKEND_CUDA) return 0;
  return horizon::backend_available(static_cast<horizon::Backend>(backend)) ? 1 : 0;
}

horizon_status horizon_search(const double* points, size_t n, int dims, const horizon_options* options,
                              horizon_list** list) {
  return guarded([&] {
    require(list, "list");
    *list = nullptr;
    require_points(points, n, dims, "points");
    const horizon::SearchOptions search = search_options(options);
    *list = new_list(horizon::search(horizon::PointView(points, n, dims), search), horizon::bond_reach(search, dims),
                     false);
  });
}

horizon_status horizon_search_radii(const double* points, size_t n, int dims, const double* radii,
                                    horizon_radius_rule rule, const horizon_options* options, horizon_list** list) {
  return guarded([&] {
    require(list, "list");
    *list = nullptr;
    require_points(points, n, dims, "points");
    if (n > 0) require(radii, "radii");
    if (rule < HORIZON_RADIUS_GATHER || rule > HORIZON_RADIUS_MIN)
      refuse("rule is " + std::to_string(rule) + ": expected HORIZON_RADIUS_GATHER, _SCATTER, _MAX or _MIN");
    horizon::SearchOptions search = search_options(options);
    horizon::NeighborList found = horizon::search_with_radii(
        horizon::PointView(points, n, dims), {radii, n}, static_cast<horizon::RadiusRule>(rule), search);
    search.horizon = largest(radii, n);
    *list = new_list(std::move(found), horizon::bond_reach(search, dims), false);
  });
}

horizon_status horizon_search_queries(const double* queries, size_t n_queries, const double* references,
                                      size_t n_references, int dims, const double* radii,
                                      const horizon_options* options, horizon_list** list) {
  return guarded([&] {
    require(list, "list");
    *list = nullptr;
    require_points(queries, n_queries, dims, "queries");
    require_points(references, n_references, dims, "references");
    const horizon::SearchOptions search = search_options(options);
    const horizon::PointView query_view(queries, n_queries, dims), reference_view(references, n_references, dims);
    *list = new_list(radii ? horizon::search_with_radii(query_view, {radii, n_queries}, reference_view, search)
                           : horizon::search(query_view, reference_view, search),
                     0, true);
  });
}

size_t horizon_list_size(const horizon_list* list) { return list ? list->list.size() : 0; }
int64_t horizon_list_total(const horizon_list* list) {
  if (list == nullptr) return 0;
  return list->list.total() - (list->one_based ? 1 : 0);  // the last offset counts from 1 too
}
const int64_t* horizon_list_offsets(const horizon_list* list) { return list ? list->list.offsets().data() : nullptr; }
const int32_t* horizon_list_indices(const horizon_list* list) { return list ? list->list.indices().data() : nullptr; }
int horizon_list_is_half(const horizon_list* list) { return list && list->list.is_half() ? 1 : 0; }
int horizon_list_is_one_based(const horizon_list* list) { return list && list->one_based ? 1 : 0; }

horizon_status horizon_list_make_one_based(horizon_list* list) {
  return guarded([&] {
    require(list, "list");
    if (list->one_based) return;
    const bool half = list->list.is_half();
    auto [offsets, indices] = std::move(list->list).release();
    for (auto& offset : offsets) ++offset;
    for (auto& id : indices) ++id;
    list->list = horizon::NeighborList(std::move(offsets), std::move(indices), half);
    list->one_based = true;
  });
}

void horizon_list_free(horizon_list* list) { delete list; }

horizon_status horizon_filter_bonds(horizon_list* list, const double* points, size_t n, int dims,
                                    const char* filters_json, int threads) {
  return guarded([&] {
    require_filterable(list);
    require_points(points, n, dims, "points");
    require(filters_json, "filters_json");
    if (n != list->list.size())
      refuse("points: " + std::to_string(n) + " points for a list of " + std::to_string(list->list.size()) + " rows");
    const auto filters = horizon::parse_bond_filters(filters_json, "filters_json");
    list->list = horizon::filter_bonds(std::move(list->list), horizon::PointView(points, n, dims), filters,
                                       list->reach, threads);
  });
}

horizon_status horizon_filter_blocks(horizon_list* list, const int32_t* blocks, const char* pairs, int threads) {
  return guarded([&] {
    require_filterable(list);
    require(pairs, "pairs");
    const std::size_t n = list->list.size();
    if (n > 0) require(blocks, "blocks");
    const std::vector<std::int32_t> block_ids(blocks, blocks + n);
    list->list = horizon::filter_blocks(std::move(list->list), block_ids, horizon::BlockPairs::parse(pairs), threads);
  });
}

horizon_status horizon_verlet_create(const double* points, size_t n, int dims, const horizon_options* options,
                                     double skin, horizon_verlet** verlet) {
  return guarded([&] {
    require(verlet, "verlet");
    *verlet = nullptr;
    require_points(points, n, dims, "points");
    *verlet = new horizon_verlet{horizon::VerletList(horizon::PointView(points, n, dims), search_options(options), skin),
                                 n, dims};
  });
}

horizon_status horizon_verlet_needs_rebuild(const horizon_verlet* verlet, const double* points, size_t n,
                                            int* needed) {
  return guarded([&] {
    require(verlet, "verlet");
    require(needed, "needed");
    require_points(points, n, verlet->dims, "points");
    *needed = verlet->verlet.needs_rebuild(horizon::PointView(points, n, verlet->dims)) ? 1 : 0;
  });
}

horizon_status horizon_verlet_refresh(const horizon_verlet* verlet, const double* points, size_t n,
                                      horizon_list** list) {
  return guarded([&] {
    require(list, "list");
    *list = nullptr;
    require(verlet, "verlet");
    require_points(points, n, verlet->dims, "points");
    *list = new_list(verlet->verlet.refresh(horizon::PointView(points, n, verlet->dims)), 0, false);
  });
}

void horizon_verlet_free(horizon_verlet* verlet) { delete verlet; }

horizon_status horizon_search_device(const double* device_points, size_t n, int dims, const horizon_options* options,
                                     void* stream, horizon_device_list** list) {
  return guarded([&] {
    require(list, "list");
    *list = nullptr;
    require_points(device_points, n, dims, "device_points");
    horizon::SearchOptions search = search_options(options);
    if (!horizon::backend_available(horizon::Backend::cuda))
      refuse("search_device needs the cuda backend, which is not available here", HORIZON_BACKEND_UNAVAILABLE);
    search.backend = horizon::Backend::cuda;
    *list = new horizon_device_list{
        horizon::search_device(device_points, n, dims, search, static_cast<horizon::cuda_stream>(stream))};
  });
}

size_t horizon_device_list_size(const horizon_device_list* list) { return list ? list->list.size() : 0; }
int64_t horizon_device_list_total(const horizon_device_list* list) { return list ? list->list.total() : 0; }
const int64_t* horizon_device_list_offsets(const horizon_device_list* list) { return list ? list->list.offsets() : nullptr; }
const int32_t* horizon_device_list_indices(const horizon_device_list* list) { return list ? list->list.indices() : nullptr; }
void horizon_device_list_free(horizon_device_list* list) { delete list; }

}  // extern "C"
