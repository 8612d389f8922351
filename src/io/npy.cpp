#include "npy.hpp"

#include <cstring>
#include <fstream>
#include <regex>

#include "atomic_file.hpp"
#include "horizon/error.hpp"

namespace horizon::detail {

namespace {

std::size_t item_size(const std::string& type) { return type == "f4" || type == "i4" ? 4 : 8; }

std::string header_field(const std::string& header, const std::string& key,
                         const std::string& path) {
  const std::regex pattern("'" + key + "'\\s*:\\s*('[^']*'|True|False|\\([^)]*\\))");
  std::smatch match;
  if (!std::regex_search(header, match, pattern))
    throw Error(path + ": .npy header has no '" + key + "'");
  return match[1];
}

}  // namespace

std::size_t NpyArray::elements() const {
  std::size_t n = 1;
  for (std::size_t s : shape) n *= s;
  return n;
}

Buffer<std::int64_t> integer_values(const NpyArray& array) {
  Buffer<std::int64_t> out(array.elements());
  for (std::size_t e = 0; e < out.size(); ++e) {
    if (array.type == "i8") {
      std::memcpy(&out[e], &array.bytes[e * 8], 8);
    } else {
      std::int32_t v;
      std::memcpy(&v, &array.bytes[e * 4], 4);
      out[e] = v;
    }
  }
  return out;
}

NpyFile open_npy(const std::string& path) {
  NpyFile file;
  std::ifstream& in = file.in;
  in.open(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open (" + std::strerror(errno) + ")");
  char preamble[8];
  if (!in.read(preamble, 8) || std::memcmp(preamble, "\x93NUMPY", 6) != 0)
    throw Error(path + ": not a .npy file (bad magic)");
  std::uint32_t header_length = 0;
  const int major = static_cast<unsigned char>(preamble[6]);
  if (major == 1) {
    unsigned char b[2];
    if (!in.read(reinterpret_cast<char*>(b), 2)) throw Error(path + ": truncated .npy header");
    header_length = b[0] | (b[1] << 8);
  } else if (major == 2 || major == 3) {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) throw Error(path + ": truncated .npy header");
    header_length = b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
  } else {
    throw Error(path + ": unsupported .npy version " + std::to_string(major));
  }
  // The header's length is checked against the file before it is allocated (a corrupt length
  // field could ask for 4 GB).
  const auto header_start = in.tellg();
  in.seekg(0, std::ios::end);
  const auto file_rest = static_cast<std::size_t>(in.tellg() - header_start);
  in.seekg(header_start);
  if (header_length > file_rest)
    throw Error(path + ": truncated .npy header (" + std::to_string(header_length) + " bytes announced, " +
                std::to_string(file_rest) + " in the file)");
  std::string header(header_length, '\0');
  if (!in.read(header.data(), header_length)) throw Error(path + ": truncated .npy header");

  NpyArray& array = file.array;
  const std::string descr = header_field(header, "descr", path);
  const std::string type = descr.substr(1, descr.size() - 2);  // drop quotes
  if (type.size() == 3 && type[0] == '>')
    throw Error(path + ": big-endian dtype " + descr + " is not supported (save as little-endian)");
  if (type != "<f8" && type != "<f4" && type != "<i4" && type != "<i8")
    throw Error(path + ": unsupported dtype " + descr + " (expected float64, float32, int32 or int64)");
  array.type = type.substr(1);
  file.fortran = header_field(header, "fortran_order", path) == "True";
  const std::string shape = header_field(header, "shape", path);
  const std::regex number("\\d+");
  for (auto it = std::sregex_iterator(shape.begin(), shape.end(), number); it != std::sregex_iterator(); ++it) {
    if (it->str().size() > 18) throw Error(path + ": shape " + shape + " is too large");
    array.shape.push_back(std::stoull(it->str()));
  }

  // The data the header promises must be in the file: checked before allocating it, so a
  // corrupt or truncated header is reported as such, not as running out of memory.
  const std::size_t size = item_size(array.type);
  std::size_t needed = size;
  for (std::size_t s : array.shape)
    if (__builtin_mul_overflow(needed, s, &needed)) throw Error(path + ": shape " + shape + " is too large");
  const auto data_start = in.tellg();
  in.seekg(0, std::ios::end);
  const auto available = static_cast<std::size_t>(in.tellg() - data_start);
  in.seekg(data_start);
  if (needed > available)
    throw Error(path + ": the header's shape " + shape + " of " + descr + " needs " + std::to_string(needed) +
                " bytes of data, the file holds " + std::to_string(available) + " (truncated or corrupt)");
  file.bytes = needed;
  return file;
}

NpyArray read_npy(const std::string& path) { return read_npy(open_npy(path), path); }

NpyArray read_npy(NpyFile file, const std::string& path) {
  NpyArray& array = file.array;
  const std::size_t size = item_size(array.type);
  std::vector<char> raw(file.bytes);
  if (!file.in.read(raw.data(), static_cast<std::streamsize>(raw.size())))
    throw Error(path + ": truncated .npy data (expected " + std::to_string(raw.size()) + " bytes)");
  if (file.fortran && array.shape.size() == 2) {
    // Column-major on disk: transpose to C order.
    const std::size_t rows = array.shape[0], cols = array.shape[1];
    array.bytes.resize(raw.size());
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c)
        std::memcpy(&array.bytes[(r * cols + c) * size], &raw[(c * rows + r) * size], size);
  } else {
    array.bytes = std::move(raw);
  }
  return std::move(array);
}

std::string npy_header(const std::string& type, const std::vector<std::size_t>& shape) {
  std::string dims;
  for (std::size_t s : shape) dims += std::to_string(s) + ", ";
  if (shape.size() > 1) dims.resize(dims.size() - 2);
  else dims.resize(dims.size() - 1);
  std::string header = "{'descr': '<" + type + "', 'fortran_order': False, 'shape': (" + dims + "), }";
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  const auto length = static_cast<std::uint16_t>(header.size());
  return std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(length & 0xff) + static_cast<char>(length >> 8) +
         header;
}

void write_npy(const std::string& path, const std::string& type,
               const std::vector<std::size_t>& shape, const void* data) {
  AtomicFile file(path);
  file.write(npy_header(type, shape));
  std::size_t elements = 1;
  for (std::size_t s : shape) elements *= s;
  file.write(data, elements * item_size(type));
  file.commit();
}

}  // namespace horizon::detail
