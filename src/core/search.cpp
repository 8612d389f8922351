#include "horizon/search.hpp"
#include "backend_choice.hpp"
#include "cell_search.hpp"
#include "parallel_copy.hpp"

#include "../backends/backends.hpp"
#include "family_search.hpp"
#include "partitioned_search.hpp"
#include "reference_search.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/grid.hpp"
#include "horizon/radii.hpp"

namespace horizon {

Backend parse_backend(const std::string& name) {
  if (name == "auto") return Backend::automatic;
  if (name == "serial") return Backend::serial;
  if (name == "openmp") return Backend::openmp;
  if (name == "cuda") return Backend::cuda;
  throw Error("unknown backend '" + name + "' (expected auto, serial, openmp or cuda)");
}

const char* backend_name(Backend backend) {
  switch (backend) {
    case Backend::automatic: return "auto";
    case Backend::serial: return "serial";
    case Backend::openmp: return "openmp";
    case Backend::cuda: return "cuda";
  }
  return "?";
}

bool backend_available(Backend backend) {
  switch (backend) {
    case Backend::automatic:
    case Backend::serial: return true;
    case Backend::openmp: return detail::openmp_built();
    case Backend::cuda: return detail::cuda_usable();
  }
  return false;
}

const char* cpu_simd_target() { return detail::simd_target(); }

void detail::validate_search(PointView points, const SearchOptions& options, bool values) {
  // The serial backend stays on one core; the others check the points on all of theirs.
  const Backend backend = options.backend;
  if (values) validate_points(points, backend == Backend::serial ? 1 : backend == Backend::openmp ? options.threads : 0);
  else validate_point_shape(points);
  validate_horizon(options.horizon, options.cells_per_horizon);
  if (options.queries > points.size())
    throw Error("queries (" + std::to_string(options.queries) + ") exceeds the " + std::to_string(points.size()) +
                " points");
}

NeighborList search(PointView points, const SearchOptions& given, SearchStats* stats) {
  const detail::BackendChoice choice = detail::choose_backend(points.size(), given);
  SearchOptions options = given;
  options.backend = choice.backend;
  options.threads = choice.threads;
  const Backend backend = options.backend;
  // One GPU checks the coordinates' values once they are uploaded (search_cuda): here they
  // would all be read once more, 3-5 ms of a 25 ms host->host search (lattice 200, H200).
  const bool available = backend_available(backend);
  const bool checked_on_gpu = available && backend == Backend::cuda && options.devices.size() <= 1;
  detail::validate_search(points, options, !checked_on_gpu);
  SearchStats local;
  SearchStats& out = stats ? *stats : local;
  out = SearchStats{};
  out.choice = choice.reason;
  if (!available)
    throw Error(std::string("backend '") + backend_name(backend) + "' is not available here");
  out.backend = backend;
  if (!options.devices.empty() && backend != Backend::cuda)
    throw Error(std::string("devices are for the cuda backend, not '") + backend_name(backend) + "'");
  if (detail::needs_cell_search(options)) {
    NeighborList list = detail::search_cell(points, options, {}, RadiusRule::gather, out);
    out.choice = choice.reason;
    return list;
  }
  if (detail::is_periodic(options)) return detail::search_periodic(points, backend, options, out);
  if (points.empty()) return NeighborList({0}, {}, options.half);
  if (backend == Backend::cuda && options.devices.size() > 1) {
    std::vector<SearchOptions> per_device;
    for (int device : options.devices) {
      SearchOptions one = options;
      one.backend = Backend::cuda;
      one.device = device;
      one.devices.clear();
      per_device.push_back(one);
    }
    return detail::search_parts(points, options, per_device, out);
  }
  if (options.devices.size() == 1) {
    SearchOptions one = options;
    one.device = options.devices[0];
    one.devices.clear();
    return search(points, one, stats);
  }

  switch (backend) {
    case Backend::openmp: return detail::search_openmp(points, options, out);
    case Backend::cuda: {
      const detail::CopyThreads copies(options.threads);
      return detail::search_cuda(points, options, out);
    }
    default: return detail::search_serial(points, options, out);
  }
}

NeighborList search(PointView queries, PointView references, const SearchOptions& given, SearchStats* stats) {
  validate(queries);
  validate(references);
  if (detail::needs_cell_search(given))
    throw Error("a cell, outputs and self_interaction are for one point set, not queries against references");
  validate_horizon(given.horizon, given.cells_per_horizon);
  const detail::BackendChoice choice = detail::choose_backend(queries.size() + references.size(), given);
  SearchOptions options = given;
  options.backend = choice.backend;
  options.threads = choice.threads;
  SearchStats local;
  SearchStats& out = stats ? *stats : local;
  NeighborList list = detail::search_references(queries, references, options, out);
  out.choice = choice.reason;
  return list;
}

void warm_up(Backend backend) {
  if (!backend_available(backend))
    throw Error(std::string("backend '") + backend_name(backend) + "' is not available here");
  const PointSet points = random_cloud(512, 3, 1, 4.0);  // a search takes every code path's dispatch
  SearchOptions options;
  options.horizon = 1.0;
  if (backend != Backend::cuda) {
    const int threads = backend == Backend::serial ? 1 : detail::usable_cpus();
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
    }
    options.backend = Backend::serial;
    search(points.view(), options);
  }
  if (backend == Backend::cuda || (backend == Backend::automatic && backend_available(Backend::cuda))) {
    options.backend = Backend::cuda;
    search(points.view(), options);
  }
}

}  // namespace horizon
