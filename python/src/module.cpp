// The compiled half of the Python package (horizon/_horizon): the search on NumPy arrays, with
// the GIL released, and the list's buffers handed to NumPy without a copy (each array keeps the
// list alive). horizon::Error becomes ValueError, running out of memory MemoryError, with the
// CLI's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "horizon/block_filter.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/cuda.hpp"
#include "horizon/generate.hpp"
#include "horizon/io.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"
#include "horizon/verlet_list.hpp"
#include "horizon/version.hpp"

namespace py = pybind11;

namespace {

/// A list owned by Python.
struct OwnedList {
  horizon::NeighborList list;
  horizon::SearchStats stats;  ///< what ran and why (searches only)
};

/// A Verlet list owned by Python (it keeps its own copy of the positions at the build).
struct OwnedVerlet {
  horizon::VerletList list;
};

/// A list in GPU memory owned by Python, with the stream it was built on (the consumers'
/// __cuda_array_interface__ names it).
struct OwnedDeviceList {
  horizon::DeviceNeighborList list;
  std::uintptr_t stream;
  int device;
  bool half;
};

/// One GPU's part of a search left on the GPUs (search_device_parts), owned by Python.
struct OwnedDevicePart {
  horizon::DevicePart part;
  bool half;
};

template <typename T>
py::array view(const T* data, std::size_t count, py::handle owner) {
  return py::array(py::dtype::of<T>(), {count}, {sizeof(T)}, data, owner);
}

horizon::SearchOptions options_of(double horizon, const std::string& metric, bool half, bool sort_rows,
                                  int cells_per_horizon) {
  horizon::SearchOptions options;
  options.horizon = horizon;
  options.metric = horizon::parse_metric(metric);
  options.half = half;
  options.sort_rows = sort_rows;
  options.cells_per_horizon = cells_per_horizon;
  return options;
}

/// A C-contiguous (N, 2|3) float64 or float32 array (the Python layer makes it so).
horizon::PointView point_view(const py::array& points) {
  const auto rows = static_cast<std::size_t>(points.shape(0));
  const int dims = static_cast<int>(points.shape(1));
  return points.dtype().is(py::dtype::of<float>())
             ? horizon::PointView(static_cast<const float*>(points.data()), rows, dims)
             : horizon::PointView(static_cast<const double*>(points.data()), rows, dims);
}

/// references: None, or the reference points (rows are then `points`, ids index references).
OwnedList search(py::array points, double horizon, const std::string& metric, bool half, bool sort_rows,
                 const std::string& backend, int threads, int device, const std::vector<int>& devices,
                 int cells_per_horizon, const std::array<double, 3>& box, std::optional<py::array> references,
                 std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> radii,
                 const std::string& radius_rule, std::size_t gpu_max_memory,
                 std::optional<std::array<std::array<double, 3>, 3>> cell, const std::array<bool, 3>& pbc,
                 bool self_interaction, const std::array<bool, 3>& outputs) {
  const horizon::PointView view = point_view(points);
  horizon::SearchOptions options = options_of(horizon, metric, half, sort_rows, cells_per_horizon);
  if (cell) options.cell = horizon::Cell{*cell, pbc};
  options.self_interaction = self_interaction;
  options.outputs = horizon::PairOutputs{outputs[0], outputs[1], outputs[2]};
  options.backend = horizon::parse_backend(backend);
  options.threads = threads;
  options.device = device;
  options.devices = devices;
  options.box = box;
  options.gpu_max_memory = gpu_max_memory;
  if (radii) {
    const std::span<const double> values(radii->data(), static_cast<std::size_t>(radii->size()));
    const horizon::RadiusRule rule = horizon::parse_radius_rule(radius_rule);
    if (references) {  // one radius per query: the gather rule only
      if (rule != horizon::RadiusRule::gather)
        throw horizon::Error(std::string("radii with references: only radius_rule='gather' (each query's own radius), not ") +
                             horizon::radius_rule_name(rule));
      const horizon::PointView reference_view = point_view(*references);
      py::gil_scoped_release unlocked;
      OwnedList owned;
      owned.list = horizon::search_with_radii(view, values, reference_view, options, &owned.stats);
      return owned;
    }
    py::gil_scoped_release unlocked;
    OwnedList owned;
    owned.list = horizon::search_with_radii(view, values, rule, options, &owned.stats);
    return owned;
  }
  OwnedList owned;
  if (references) {
    const horizon::PointView reference_view = point_view(*references);
    py::gil_scoped_release unlocked;
    owned.list = horizon::search(view, reference_view, options, &owned.stats);
    return owned;
  }
  py::gil_scoped_release unlocked;
  owned.list = horizon::search(view, options, &owned.stats);
  return owned;
}

OwnedVerlet build_verlet(py::array points, double horizon, double skin, const std::string& metric, bool half,
                         bool sort_rows, const std::string& backend, int threads, int device, int cells_per_horizon) {
  const horizon::PointView view = point_view(points);
  horizon::SearchOptions options = options_of(horizon, metric, half, sort_rows, cells_per_horizon);
  options.backend = horizon::parse_backend(backend);
  options.threads = threads;
  options.device = device;
  py::gil_scoped_release unlocked;
  return OwnedVerlet{horizon::VerletList(view, options, skin)};
}

/// A list copied from NumPy's int64 offsets and int32 indices.
horizon::NeighborList list_of(const py::array_t<std::int64_t>& offsets, const py::array_t<std::int32_t>& indices,
                              bool half) {
  horizon::Buffer<std::int64_t> row_offsets(offsets.data(), offsets.data() + offsets.size());
  horizon::Buffer<horizon::point_id> row_indices(indices.data(), indices.data() + indices.size());
  return horizon::NeighborList(std::move(row_offsets), std::move(row_indices), half);
}

/// The list and its points (and their blocks, when given) to a .vtu file.
void write_vtk(const std::string& path, py::array points, py::array_t<std::int64_t> offsets,
               py::array_t<std::int32_t> indices, bool half, bool bonds, std::vector<std::int32_t> blocks) {
  horizon::PointSet set = horizon::to_point_set(point_view(points));
  set.blocks = std::move(blocks);
  const horizon::NeighborList list = list_of(offsets, indices, half);
  py::gil_scoped_release unlocked;
  horizon::write_vtk(path, set, list, bonds);
}

/// The list without the bonds crossing the filters (JSON text, named `source` in errors).
OwnedList filter_bonds(py::array_t<std::int64_t> offsets, py::array_t<std::int32_t> indices, bool half,
                       py::array points, std::optional<py::array> references, const std::string& json,
                       const std::string& source, int threads) {
  const auto filters = horizon::parse_bond_filters(json, source);
  horizon::NeighborList list = list_of(offsets, indices, half);
  const horizon::PointView rows = point_view(points), columns = references ? point_view(*references) : rows;
  py::gil_scoped_release unlocked;
  return OwnedList{horizon::filter_bonds(std::move(list), rows, columns, filters, 0, threads)};
}

/// The list without the bonds between blocks that are not one of `pairs` ("1-1,1-2").
OwnedList filter_blocks(py::array_t<std::int64_t> offsets, py::array_t<std::int32_t> indices, bool half,
                        const std::vector<std::int32_t>& blocks, const std::vector<std::int32_t>& reference_blocks,
                        const std::string& pairs, int threads) {
  const horizon::BlockPairs block_pairs = horizon::BlockPairs::parse(pairs);
  horizon::NeighborList list = list_of(offsets, indices, half);
  py::gil_scoped_release unlocked;
  return OwnedList{horizon::filter_blocks(std::move(list), blocks, reference_blocks, block_pairs, threads)};
}

/// points: `count` x `dims` C-contiguous float64 in GPU memory at `pointer`; the list is built on
/// `stream` (a CUDA stream handle, 0 for the default stream) of the device holding the points.
/// box, cell, pbc, self_interaction and outputs as search()'s.
OwnedDeviceList search_device(std::uintptr_t pointer, std::size_t count, int dims, std::uintptr_t stream,
                              double horizon, const std::string& metric, bool half, bool sort_rows,
                              int cells_per_horizon, const std::array<double, 3>& box,
                              std::optional<std::array<std::array<double, 3>, 3>> cell,
                              const std::array<bool, 3>& pbc, bool self_interaction,
                              const std::array<bool, 3>& outputs) {
  const auto* xyz = reinterpret_cast<const double*>(pointer);
  horizon::SearchOptions options = options_of(horizon, metric, half, sort_rows, cells_per_horizon);
  options.box = box;
  if (cell) options.cell = horizon::Cell{*cell, pbc};
  options.self_interaction = self_interaction;
  options.outputs = horizon::PairOutputs{outputs[0], outputs[1], outputs[2]};
  py::gil_scoped_release unlocked;
  options.device = count ? horizon::cuda_use_device_of(xyz) : 0;
  auto list = horizon::search_device(xyz, count, dims, options, reinterpret_cast<horizon::cuda_stream>(stream));
  return OwnedDeviceList{std::move(list), stream, options.device, half};
}

/// `points` cut into one part per entry of `devices`, each part's rows left on its GPU.
std::vector<OwnedDevicePart> search_device_parts(py::array points, double horizon, const std::string& metric,
                                                 bool half, bool sort_rows, int device,
                                                 const std::vector<int>& devices, int cells_per_horizon,
                                                 std::size_t gpu_max_memory) {
  const horizon::PointView view = point_view(points);
  horizon::SearchOptions options = options_of(horizon, metric, half, sort_rows, cells_per_horizon);
  options.backend = horizon::Backend::cuda;
  options.device = device;
  options.devices = devices;
  options.gpu_max_memory = gpu_max_memory;
  py::gil_scoped_release unlocked;
  std::vector<OwnedDevicePart> parts;
  for (horizon::DevicePart& part : horizon::search_device_parts(view, options)) parts.push_back({std::move(part), half});
  return parts;
}

/// A property of OwnedList: one of its list's arrays as a NumPy view that keeps the list alive.
template <typename T>
auto list_array(const horizon::Buffer<T>& (horizon::NeighborList::*array)() const) {
  return [array](py::object self) {
    const horizon::Buffer<T>& values = (self.cast<const OwnedList&>().list.*array)();
    return view(values.data(), values.size(), self);
  };
}

py::array to_array(const horizon::PointSet& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), static_cast<py::ssize_t>(points.dims)});
  std::memcpy(out.mutable_data(), points.xyz.data(), points.xyz.size() * sizeof(double));
  return out;
}

}  // namespace

PYBIND11_MODULE(_horizon, m) {
  m.doc() = "horizon's compiled core; use the horizon package";
  m.attr("__version__") = horizon::version();
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const horizon::DeviceOutOfMemory& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    } catch (const horizon::ListTooLarge& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    } catch (const horizon::Error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "out of memory (the neighbour list does not fit)");
    }
  });

  py::class_<OwnedList>(m, "OwnedList")
      .def_property_readonly("offsets", list_array(&horizon::NeighborList::offsets))
      .def_property_readonly("indices", list_array(&horizon::NeighborList::indices))
      .def_property_readonly("shifts", list_array(&horizon::NeighborList::shifts))
      .def_property_readonly("distances", list_array(&horizon::NeighborList::distances))
      .def_property_readonly("vectors", list_array(&horizon::NeighborList::vectors))
      .def_property_readonly("backend", [](const OwnedList& l) { return std::string(horizon::backend_name(l.stats.backend)); })
      .def_property_readonly("threads", [](const OwnedList& l) { return l.stats.threads; })
      .def_property_readonly("choice", [](const OwnedList& l) { return l.stats.choice; });

  py::class_<OwnedVerlet>(m, "OwnedVerlet")
      .def("needs_rebuild", [](const OwnedVerlet& v, py::array points, int threads) {
        const horizon::PointView view = point_view(points);
        py::gil_scoped_release unlocked;
        return v.list.needs_rebuild(view, threads);
      })
      .def("refresh", [](const OwnedVerlet& v, py::array points, int threads) {
        const horizon::PointView view = point_view(points);
        py::gil_scoped_release unlocked;
        return OwnedList{v.list.refresh(view, threads)};
      })
      .def_property_readonly("candidate_offsets", [](py::object self) {
        const auto& list = self.cast<const OwnedVerlet&>().list.candidates();
        return view(list.offsets().data(), list.offsets().size(), self);
      })
      .def_property_readonly("candidate_indices", [](py::object self) {
        const auto& list = self.cast<const OwnedVerlet&>().list.candidates();
        return view(list.indices().data(), list.indices().size(), self);
      });

  py::class_<OwnedDeviceList>(m, "OwnedDeviceList")
      .def_property_readonly("offsets_pointer", [](const OwnedDeviceList& l) { return reinterpret_cast<std::uintptr_t>(l.list.offsets()); })
      .def_property_readonly("indices_pointer", [](const OwnedDeviceList& l) { return reinterpret_cast<std::uintptr_t>(l.list.indices()); })
      .def_property_readonly("shifts_pointer", [](const OwnedDeviceList& l) { return reinterpret_cast<std::uintptr_t>(l.list.shifts()); })
      .def_property_readonly("distances_pointer", [](const OwnedDeviceList& l) { return reinterpret_cast<std::uintptr_t>(l.list.distances()); })
      .def_property_readonly("vectors_pointer", [](const OwnedDeviceList& l) { return reinterpret_cast<std::uintptr_t>(l.list.vectors()); })
      .def_property_readonly("points", [](const OwnedDeviceList& l) { return l.list.size(); })
      .def_property_readonly("total", [](const OwnedDeviceList& l) { return l.list.total(); })
      .def_property_readonly("stream", [](const OwnedDeviceList& l) { return l.stream; })
      .def_property_readonly("device", [](const OwnedDeviceList& l) { return l.device; })
      .def("to_host", [](const OwnedDeviceList& l) {
        py::gil_scoped_release unlocked;
        return OwnedList{l.list.to_host(l.half)};
      });

  py::class_<OwnedDevicePart>(m, "OwnedDevicePart")
      .def_property_readonly("offsets_pointer", [](const OwnedDevicePart& p) { return reinterpret_cast<std::uintptr_t>(p.part.rows.offsets()); })
      .def_property_readonly("indices_pointer", [](const OwnedDevicePart& p) { return reinterpret_cast<std::uintptr_t>(p.part.rows.indices()); })
      .def_property_readonly("ids_pointer", [](const OwnedDevicePart& p) { return reinterpret_cast<std::uintptr_t>(p.part.device_ids.get()); })
      .def_property_readonly("ids", [](py::object self) {
        const auto& ids = self.cast<const OwnedDevicePart&>().part.ids;
        return view(ids.data(), ids.size(), self);
      })
      .def_property_readonly("points", [](const OwnedDevicePart& p) { return p.part.rows.size(); })
      .def_property_readonly("total", [](const OwnedDevicePart& p) { return p.part.rows.total(); })
      .def_property_readonly("halo", [](const OwnedDevicePart& p) { return p.part.halo; })
      .def_property_readonly("stream", [](const OwnedDevicePart& p) { return reinterpret_cast<std::uintptr_t>(p.part.rows.stream()); })
      .def_property_readonly("device", [](const OwnedDevicePart& p) { return p.part.device; })
      .def("to_host", [](const OwnedDevicePart& p) {
        py::gil_scoped_release unlocked;
        return OwnedList{p.part.rows.to_host(p.half)};
      });

  m.def("search_device_parts", &search_device_parts, py::arg("points"), py::arg("horizon"), py::arg("metric"),
        py::arg("half"), py::arg("sort_rows"), py::arg("device"), py::arg("devices"), py::arg("cells_per_horizon"),
        py::arg("gpu_max_memory"));
  m.def("search_device", &search_device, py::arg("pointer"), py::arg("count"), py::arg("dims"), py::arg("stream"),
        py::arg("horizon"), py::arg("metric"), py::arg("half"), py::arg("sort_rows"), py::arg("cells_per_horizon"),
        py::arg("box"), py::arg("cell"), py::arg("pbc"), py::arg("self_interaction"), py::arg("outputs"));
  m.def("search", &search, py::arg("points"), py::arg("horizon"), py::arg("metric"), py::arg("half"),
        py::arg("sort_rows"), py::arg("backend"), py::arg("threads"), py::arg("device"), py::arg("devices"),
        py::arg("cells_per_horizon"), py::arg("box"), py::arg("references"), py::arg("radii"),
        py::arg("radius_rule"), py::arg("gpu_max_memory"), py::arg("cell"), py::arg("pbc"),
        py::arg("self_interaction"), py::arg("outputs"));
  m.def("build_verlet", &build_verlet, py::arg("points"), py::arg("horizon"), py::arg("skin"), py::arg("metric"),
        py::arg("half"), py::arg("sort_rows"), py::arg("backend"), py::arg("threads"), py::arg("device"),
        py::arg("cells_per_horizon"));
  m.def("write_vtk", &write_vtk, py::arg("path"), py::arg("points"), py::arg("offsets"), py::arg("indices"),
        py::arg("half"), py::arg("bonds"), py::arg("blocks"));
  m.def("filter_bonds", &filter_bonds, py::arg("offsets"), py::arg("indices"), py::arg("half"), py::arg("points"),
        py::arg("references"), py::arg("json"), py::arg("source"), py::arg("threads"));
  m.def("filter_blocks", &filter_blocks, py::arg("offsets"), py::arg("indices"), py::arg("half"), py::arg("blocks"),
        py::arg("reference_blocks"), py::arg("pairs"), py::arg("threads"));
  m.def("lattice", [](int n, int dims, double side) { return to_array(horizon::lattice(n, dims, side)); });
  m.def("random_cloud", [](std::size_t count, int dims, std::uint64_t seed, double side) {
    return to_array(horizon::random_cloud(count, dims, seed, side));
  });
  m.def("clustered_cloud", [](std::size_t count, int clusters, double sigma, int dims, std::uint64_t seed,
                              double side) {
    return to_array(horizon::clustered_cloud(count, clusters, sigma, dims, seed, side));
  });
  m.def("warm_up", [](const std::string& backend) {
    const horizon::Backend parsed = horizon::parse_backend(backend);
    py::gil_scoped_release unlocked;
    horizon::warm_up(parsed);
  });
  m.def("backend_available", [](const std::string& name) {
    return horizon::backend_available(horizon::parse_backend(name));
  });
}
