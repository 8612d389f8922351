#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "atomic_file.hpp"
#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "npy.hpp"
#include "parse_number.hpp"
#include "../core/parallel_copy.hpp"

namespace horizon {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

PointSet points_from_npy(const std::string& path) {
  detail::NpyFile file = detail::open_npy(path);
  const detail::NpyArray& header = file.array;
  if (header.shape.size() != 2 || (header.shape[1] != 2 && header.shape[1] != 3))
    throw Error(path + ": expected an N x 2 or N x 3 array of points");
  if (header.type != "f8" && header.type != "f4")
    throw Error(path + ": expected float64 or float32 coordinates, found " + header.type);
  const int dims = static_cast<int>(header.shape[1]);
  std::vector<double> xyz;
  if (header.type == "f8" && !file.fortran) {
    // Straight from the file into the points' storage, faulted in as huge pages where the kernel
    // offers them: one copy (a staging buffer, then a conversion loop into zeroed memory took
    // 0.17 s for 10^6 points on the 2-core VM, where each fresh 4 KB page is a slow fault).
    xyz.reserve(header.elements());
    detail::advise_huge_pages(xyz.data(), header.elements() * sizeof(double));
    xyz.resize(header.elements());
    if (!file.in.read(reinterpret_cast<char*>(xyz.data()), static_cast<std::streamsize>(file.bytes)))
      throw Error(path + ": truncated .npy data (expected " + std::to_string(file.bytes) + " bytes)");
  } else {
    const detail::NpyArray array = detail::read_npy(std::move(file), path);  // float32, or Fortran order
    xyz.resize(array.elements());
    for (std::size_t e = 0; e < xyz.size(); ++e) {
      if (array.type == "f8") {
        std::memcpy(&xyz[e], &array.bytes[e * 8], 8);
      } else {
        float f;
        std::memcpy(&f, &array.bytes[e * 4], 4);
        xyz[e] = f;
      }
    }
  }
  try {  // on all cores, vectorised; the first bad point named
    detail::check_finite(PointView(xyz.data(), xyz.size() / static_cast<std::size_t>(dims), dims), 0);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  return PointSet{dims, std::move(xyz)};
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ',' || std::isspace(static_cast<unsigned char>(line[i])))) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ',' && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

using detail::parse_number;

/// A block id: an integer from 0 to 2^31 - 1.
bool is_block_id(double v) { return v >= 0 && v <= 2147483647.0 && v == std::floor(v); }

/// visit(fields, line number) for every line of the text file `path` that has fields once its
/// `#` comment is dropped.
template <class Visit>
void for_each_line(const std::string& path, Visit visit) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::string_view text(line);
    if (const auto hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
    const auto fields = split_fields(text);
    if (!fields.empty()) visit(fields, number);
  }
}

// Text: `x y [z]` points, or Peridigm's `x y z block_id volume` (the first three columns).
PointSet points_from_text(const std::string& path) {
  PointSet set{0, {}};
  std::size_t columns = 0;
  bool header_seen = false;
  for_each_line(path, [&](const std::vector<std::string_view>& fields, std::size_t number) {
    const std::string where = path + ":" + std::to_string(number) + ": ";
    double values[5];
    if (columns == 0) {
      // A first line of names only (x,y,z) is a header.
      bool names_only = !header_seen;
      for (const auto field : fields) names_only = names_only && !parse_number(field, values[0]);
      if (names_only) {
        header_seen = true;
        return;
      }
      if (fields.size() != 2 && fields.size() != 3 && fields.size() != 5)
        throw Error(where + "expected 2 or 3 columns (x y [z]) or 5 (Peridigm: x y z block volume), found " +
                    std::to_string(fields.size()));
      columns = fields.size();
      set.dims = columns == 2 ? 2 : 3;
    }
    if (fields.size() != columns)
      throw Error(where + "expected " + std::to_string(columns) + " columns, found " +
                  std::to_string(fields.size()));
    for (std::size_t f = 0; f < fields.size(); ++f)
      if (!parse_number(fields[f], values[f]))
        throw Error(where + "'" + std::string(fields[f]) + "' is not a number");
    for (int a = 0; a < set.dims; ++a) {
      if (!std::isfinite(values[a]))
        throw Error(where + "non-finite coordinate '" + std::string(fields[a]) + "'");
      set.xyz.push_back(values[a]);
    }
    if (columns == 5) {  // Peridigm's block id
      if (!is_block_id(values[3]))
        throw Error(where + "block id '" + std::string(fields[3]) + "' is not an integer from 0 to 2^31 - 1");
      set.blocks.push_back(static_cast<std::int32_t>(values[3]));
    }
  });
  if (set.dims == 0) set.dims = 3;  // an empty file: no points
  return set;
}

}  // namespace

std::vector<std::int32_t> read_blocks(const std::string& path, std::size_t points) {
  std::vector<std::int32_t> blocks;
  if (ends_with(path, ".npy")) {
    const detail::NpyArray array = detail::read_npy(path);
    if (array.shape.size() != 1 || array.type[0] != 'i')
      throw Error(path + ": expected a 1-D array of integer block ids");
    for (const std::int64_t v : detail::integer_values(array)) {
      if (!is_block_id(static_cast<double>(v)))
        throw Error(path + ": block id " + std::to_string(v) + " of point " + std::to_string(blocks.size()) +
                    " is not from 0 to 2^31 - 1");
      blocks.push_back(static_cast<std::int32_t>(v));
    }
  } else {
    for_each_line(path, [&](const std::vector<std::string_view>& fields, std::size_t number) {
      double v = -1;
      if (fields.size() != 1 || !parse_number(fields[0], v) || !is_block_id(v))
        throw Error(path + ":" + std::to_string(number) + ": expected one block id (an integer from 0 to 2^31 - 1)");
      blocks.push_back(static_cast<std::int32_t>(v));
    });
  }
  if (blocks.size() != points)
    throw Error(path + ": " + std::to_string(blocks.size()) + " block ids for " + std::to_string(points) + " points");
  return blocks;
}

std::vector<double> read_radii(const std::string& path, std::size_t points, const std::string& rows) {
  std::vector<double> radii;
  if (ends_with(path, ".npy")) {
    const detail::NpyArray array = detail::read_npy(path);
    if (array.shape.size() != 1 || array.type[0] != 'f')
      throw Error(path + ": expected a 1-D array of radii (float64 or float32)");
    radii.resize(array.elements());
    for (std::size_t i = 0; i < radii.size(); ++i) {
      if (array.type == "f8") {
        std::memcpy(&radii[i], array.bytes.data() + 8 * i, 8);
      } else {
        float r = 0;
        std::memcpy(&r, array.bytes.data() + 4 * i, 4);
        radii[i] = r;
      }
    }
  } else {
    for_each_line(path, [&](const std::vector<std::string_view>& fields, std::size_t number) {
      double r = 0;
      if (fields.size() != 1 || !parse_number(fields[0], r))
        throw Error(path + ":" + std::to_string(number) + ": expected one radius (a number)");
      radii.push_back(r);
    });
  }
  if (radii.size() != points)
    throw Error(path + ": " + std::to_string(radii.size()) + " radii for " + std::to_string(points) + " " + rows);
  return radii;
}

PointSet read_points(const std::string& path) {
  return ends_with(path, ".npy") ? points_from_npy(path) : points_from_text(path);
}

void write_points(const std::string& path, const PointSet& points) {
  if (ends_with(path, ".npy")) {
    detail::write_npy(path, "f8", {points.size(), static_cast<std::size_t>(points.dims)},
                      points.xyz.data());
    return;
  }
  detail::AtomicFile file(path);
  std::string text;
  char number[32];
  for (std::size_t i = 0; i < points.xyz.size(); ++i) {
    const auto end = std::to_chars(number, number + sizeof number, points.xyz[i]).ptr;
    text.append(number, end);
    text += (i + 1) % static_cast<std::size_t>(points.dims) == 0 ? '\n' : ' ';
    if (text.size() > (1 << 20)) {
      file.write(text);
      text.clear();
    }
  }
  file.write(text);
  file.commit();
}

}  // namespace horizon
