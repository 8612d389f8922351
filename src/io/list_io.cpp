#include <sys/statvfs.h>

#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "atomic_file.hpp"
#include "horizon/batched_search.hpp"
#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "npy.hpp"

namespace horizon {

namespace {

void write_csv(const std::string& path, const NeighborList& list) {
  detail::AtomicFile file(path);
  std::string text = "i,j\n";
  char number[24];
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto row_id = std::to_chars(number, number + sizeof number, i).ptr;
    const std::string_view row(number, static_cast<std::size_t>(row_id - number));
    for (point_id j : list.row(i)) {
      text.append(row);
      text += ',';
      char other[16];
      text.append(other, std::to_chars(other, other + sizeof other, j).ptr);
      text += '\n';
    }
    if (text.size() > (1 << 20)) {
      file.write(text);
      text.clear();
    }
  }
  file.write(text);
  file.commit();
}

NeighborList read_csv(const std::string& path, std::size_t points, bool half) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  Buffer<std::int64_t> offsets(points + 1, 0);
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (number == 1 && line == "i,j") continue;
    std::int64_t i = -1, j = -1;
    const auto comma = line.find(',');
    const bool parsed =
        comma != std::string::npos &&
        std::from_chars(line.data(), line.data() + comma, i).ec == std::errc() &&
        std::from_chars(line.data() + comma + 1, line.data() + line.size(), j).ec == std::errc();
    if (!parsed || i < 0 || j < 0 || static_cast<std::size_t>(i) >= points ||
        static_cast<std::size_t>(j) >= points)
      throw Error(path + ":" + std::to_string(number) + ": expected 'i,j' with ids below " +
                  std::to_string(points));
    if (!pairs.empty() && pairs.back().first > i)
      throw Error(path + ":" + std::to_string(number) + ": rows out of order");
    pairs.emplace_back(i, j);
    ++offsets[static_cast<std::size_t>(i) + 1];
  }
  for (std::size_t i = 0; i < points; ++i) offsets[i + 1] += offsets[i];
  Buffer<point_id> indices;
  indices.reserve(pairs.size());
  for (const auto& [i, j] : pairs) indices.push_back(static_cast<point_id>(j));
  return NeighborList(std::move(offsets), std::move(indices), half);
}

NeighborList read_npy_list(const std::string& prefix, std::size_t points, bool half) {
  const std::string offsets_path = prefix + ".offsets.npy", indices_path = prefix + ".indices.npy";
  const auto offsets_array = detail::read_npy(offsets_path);
  const auto indices_array = detail::read_npy(indices_path);
  if (offsets_array.shape.size() != 1 || offsets_array.type[0] != 'i')
    throw Error(offsets_path + ": expected a 1-D integer array");
  if (indices_array.shape.size() != 1 || indices_array.type[0] != 'i')
    throw Error(indices_path + ": expected a 1-D integer array");
  auto offsets = detail::integer_values(offsets_array);
  if (offsets.size() != points + 1)
    throw Error(offsets_path + ": has " + std::to_string(offsets.size()) + " entries, expected " +
                std::to_string(points + 1) + " (points + 1)");
  const auto raw = detail::integer_values(indices_array);
  if (offsets.front() != 0 || offsets.back() != static_cast<std::int64_t>(raw.size()))
    throw Error(offsets_path + ": offsets do not span " + indices_path);
  for (std::size_t i = 0; i < points; ++i)
    if (offsets[i + 1] < offsets[i]) throw Error(offsets_path + ": offsets decrease at row " + std::to_string(i));
  Buffer<point_id> indices(raw.size());
  for (std::size_t e = 0; e < raw.size(); ++e) {
    if (raw[e] < 0 || static_cast<std::size_t>(raw[e]) >= points)
      throw Error(indices_path + ": entry " + std::to_string(e) + " is not a point id");
    indices[e] = static_cast<point_id>(raw[e]);
  }
  return NeighborList(std::move(offsets), std::move(indices), half);
}

}  // namespace

std::string write_neighbor_list(const std::string& prefix, const NeighborList& list,
                                ListFormat format) {
  if (format == ListFormat::csv && list.outputs().any())
    throw Error(prefix + ": shifts, distances and vectors are written as .npy files, not csv");
  if (format == ListFormat::csv) {
    write_csv(prefix + ".csv", list);
    return prefix + ".csv";
  }
  // Offsets go last: when they are in place, the indices (and geometry) they describe are complete.
  const std::string offsets_path = prefix + ".offsets.npy", indices_path = prefix + ".indices.npy";
  const std::size_t entries = list.indices().size(), dims = static_cast<std::size_t>(list.geometry_dims());
  std::string written = offsets_path + "," + indices_path;
  if (list.outputs().shifts) {
    detail::write_npy(prefix + ".shifts.npy", "i4", {entries, dims}, list.shifts().data());
    written += "," + prefix + ".shifts.npy";
  }
  if (list.outputs().distances) {
    detail::write_npy(prefix + ".distances.npy", "f8", {entries}, list.distances().data());
    written += "," + prefix + ".distances.npy";
  }
  if (list.outputs().vectors) {
    detail::write_npy(prefix + ".vectors.npy", "f8", {entries, dims}, list.vectors().data());
    written += "," + prefix + ".vectors.npy";
  }
  detail::write_npy(indices_path, "i4", {entries}, list.indices().data());
  detail::write_npy(offsets_path, "i8", {list.offsets().size()}, list.offsets().data());
  return written;
}

std::int64_t write_neighbor_list_in_batches(const std::string& prefix, PointView points, const SearchOptions& options,
                                           std::int64_t batch_entries, SearchStats* stats) {
  const std::string offsets_path = prefix + ".offsets.npy", indices_path = prefix + ".indices.npy";
  std::optional<detail::AtomicFile> offsets_file, indices_file;
  const std::int64_t* row_offsets = nullptr;  // the search's, alive until it returns
  std::int64_t row_offsets_total = 0;
  RowBatchSink sink;
  sink.begin = [&](const std::int64_t* offsets, std::size_t rows) {
    row_offsets = offsets;
    row_offsets_total = offsets[rows];
    const std::string offsets_header = detail::npy_header("i8", {rows + 1});
    const std::string indices_header = detail::npy_header("i4", {static_cast<std::size_t>(offsets[rows])});
    const std::size_t needed = offsets_header.size() + (rows + 1) * sizeof(std::int64_t) + indices_header.size() +
                               static_cast<std::size_t>(offsets[rows]) * sizeof(point_id);
    const std::filesystem::path directory = std::filesystem::absolute(indices_path).parent_path();
    struct statvfs disk {};
    if (statvfs(directory.c_str(), &disk) == 0 && needed > static_cast<std::size_t>(disk.f_bavail) * disk.f_frsize)
      throw Error(prefix + ": the neighbour list needs " + std::to_string(needed) + " bytes on disk, " +
                  std::to_string(static_cast<std::size_t>(disk.f_bavail) * disk.f_frsize) + " are free in " +
                  directory.string());
    indices_file.emplace(indices_path);
    indices_file->write(indices_header);
    offsets_file.emplace(offsets_path);
    offsets_file->write(offsets_header);
    offsets_file->write(offsets, (rows + 1) * sizeof(std::int64_t));
  };
  sink.rows = [&](std::size_t first, std::size_t last, const point_id* ids) {
    indices_file->write(ids, static_cast<std::size_t>(row_offsets[last] - row_offsets[first]) * sizeof(point_id));
  };
  search_in_batches(points, options, batch_entries, sink, stats);
  // Offsets go last: when they are in place, the indices they describe are complete.
  indices_file->commit();
  offsets_file->commit();
  return row_offsets_total;
}

NeighborList read_neighbor_list(const std::string& prefix, std::size_t points, bool half) {
  std::ifstream csv(prefix + ".csv");
  if (csv.good()) return read_csv(prefix + ".csv", points, half);
  return read_npy_list(prefix, points, half);
}

}  // namespace horizon
