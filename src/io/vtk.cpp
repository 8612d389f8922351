// ParaView output: the points as a VTK XML UnstructuredGrid (.vtu), little-endian raw appended
// data, each point a vertex cell carrying its family size; with bonds, also one line cell per pair.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "atomic_file.hpp"
#include "horizon/error.hpp"
#include "horizon/io.hpp"

namespace horizon {

namespace {

constexpr std::uint8_t vtk_vertex = 1, vtk_line = 3;

/// One appended array: its XML element (with its offset into the appended block) and its bytes.
class AppendedData {
public:
  template <typename T>
  void add(const std::string& element_head, const std::vector<T>& values) {
    xml_ += element_head + " format=\"appended\" offset=\"" + std::to_string(offset_) + "\"/>\n";
    arrays_.emplace_back(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    offset_ += sizeof(std::uint64_t) + values.size() * sizeof(T);
  }
  std::string take_xml() { return std::exchange(xml_, {}); }
  void write(detail::AtomicFile& file) const {
    file.write("  <AppendedData encoding=\"raw\">\n   _");
    for (const auto& [data, bytes] : arrays_) {
      const std::uint64_t size = bytes;  // header_type UInt64: each array's byte count first
      file.write(&size, sizeof size);
      file.write(data, bytes);
    }
    file.write("\n  </AppendedData>\n");
  }

private:
  std::string xml_;
  std::vector<std::pair<const char*, std::size_t>> arrays_;
  std::uint64_t offset_ = 0;
};

}  // namespace

void write_vtk(const std::string& path, const PointSet& points, const NeighborList& list, bool bonds,
               std::span<const double> radii) {
  const std::size_t n = points.size();
  if (list.size() != n)
    throw Error(path + ": the list has " + std::to_string(list.size()) + " rows for " + std::to_string(n) + " points");
  // Each pair once: a full list holds it twice, a half list once.
  const std::uint64_t pairs = bonds ? static_cast<std::uint64_t>(list.is_half() ? list.total() : list.total() / 2) : 0;
  if (pairs > max_vtk_bonds)
    throw Error(path + ": " + std::to_string(pairs) + " bonds are more than the " + std::to_string(max_vtk_bonds) +
                " --vtk-bonds writes (ParaView would not draw them usefully); drop --vtk-bonds or use a smaller horizon");

  std::vector<double> xyz(3 * n, 0.0);
  std::vector<std::int64_t> family(n), connectivity, cell_end;
  std::vector<std::uint8_t> types;
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < points.dims; ++a) xyz[3 * i + a] = points.xyz[i * points.dims + a];
    family[i] = static_cast<std::int64_t>(list.row(i).size());
  }
  connectivity.reserve(n + 2 * pairs);
  cell_end.reserve(n + pairs);
  types.reserve(n + pairs);
  for (std::size_t i = 0; i < n; ++i) {
    connectivity.push_back(static_cast<std::int64_t>(i));
    cell_end.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(vtk_vertex);
  }
  if (bonds)
    for (std::size_t i = 0; i < n; ++i)
      for (point_id j : list.row(i))
        if (static_cast<std::size_t>(j) > i) {  // a half list holds only these
          connectivity.push_back(static_cast<std::int64_t>(i));
          connectivity.push_back(j);
          cell_end.push_back(static_cast<std::int64_t>(connectivity.size()));
          types.push_back(vtk_line);
        }

  AppendedData data;
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      " <UnstructuredGrid>\n  <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" +
      std::to_string(types.size()) + "\">\n   <PointData Scalars=\"family_size\">\n";
  data.add("    <DataArray type=\"Int64\" Name=\"family_size\"", family);
  if (!points.blocks.empty()) {
    if (points.blocks.size() != n)
      throw Error(path + ": " + std::to_string(points.blocks.size()) + " block ids for " + std::to_string(n) + " points");
    data.add("    <DataArray type=\"Int32\" Name=\"block\"", points.blocks);
  }
  const std::vector<double> radius(radii.begin(), radii.end());
  if (!radius.empty()) {
    if (radius.size() != n)
      throw Error(path + ": " + std::to_string(radius.size()) + " radii for " + std::to_string(n) + " points");
    data.add("    <DataArray type=\"Float64\" Name=\"radius\"", radius);
  }
  xml += data.take_xml() + "   </PointData>\n   <Points>\n";
  data.add("    <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"", xyz);
  xml += data.take_xml() + "   </Points>\n   <Cells>\n";
  data.add("    <DataArray type=\"Int64\" Name=\"connectivity\"", connectivity);
  data.add("    <DataArray type=\"Int64\" Name=\"offsets\"", cell_end);
  data.add("    <DataArray type=\"UInt8\" Name=\"types\"", types);
  xml += data.take_xml() + "   </Cells>\n  </Piece>\n </UnstructuredGrid>\n";

  detail::AtomicFile file(path);
  file.write(xml);
  data.write(file);
  file.write("</VTKFile>\n");
  file.commit();
}

}  // namespace horizon
