#pragma once
// NumPy .npy files (format versions 1-3): little-endian f4, f8, i4, i8 arrays.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "horizon/buffer.hpp"

namespace horizon::detail {

struct NpyArray {
  std::string type;                 ///< "f4", "f8", "i4" or "i8"
  std::vector<std::size_t> shape;
  std::vector<char> bytes;          ///< C order
  std::size_t elements() const;
};

/// The values of an "i4" or "i8" array as int64.
Buffer<std::int64_t> integer_values(const NpyArray& array);

/// A .npy file read up to its data: the dtype and shape (`array`, no bytes yet), the layout and
/// the data's size, checked against the file's; `in` stands at the data.
struct NpyFile {
  std::ifstream in;
  NpyArray array;
  bool fortran = false;
  std::size_t bytes = 0;
};

/// Throws horizon::Error naming `path` for a missing file, a bad header, a big-endian or
/// unsupported dtype, or too few bytes.
NpyFile open_npy(const std::string& path);

/// The whole array in C order (errors as open_npy's).
NpyArray read_npy(const std::string& path);
/// The rest of an opened file's array, in C order.
NpyArray read_npy(NpyFile file, const std::string& path);

/// The bytes before the data of a version 1.0 .npy file of this dtype and shape (a multiple of 64).
std::string npy_header(const std::string& type, const std::vector<std::size_t>& shape);

/// Writes `data` (C order) under a temporary name, then renames it to `path`.
void write_npy(const std::string& path, const std::string& type,
               const std::vector<std::size_t>& shape, const void* data);

}  // namespace horizon::detail
