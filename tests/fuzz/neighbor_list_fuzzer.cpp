// libFuzzer target: any bytes as a neighbour list for `horizon verify` (read_neighbor_list).
// Byte 0: bit 0 half, bit 1 CSV (else the .npy pair); byte 1: the number of points (0-255);
// CSV: the rest is PREFIX.csv; npy: bytes 2-3 give the length L of PREFIX.offsets.npy, the next
// L bytes are it and the rest is PREFIX.indices.npy. A list it accepts must be a valid CSR.
#include <algorithm>

#include "fuzz_input.hpp"
#include "horizon/error.hpp"
#include "horizon/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using horizon::fuzz::require;
  using horizon::fuzz::write_input;
  if (size < 4) return 0;
  const bool half = data[0] & 1, csv = data[0] & 2;
  const std::size_t points = data[1];
  data += 2;
  size -= 2;
  const std::string prefix = horizon::fuzz::scratch_path("list");
  for (const char* tail : {".csv", ".offsets.npy", ".indices.npy"}) std::remove((prefix + tail).c_str());
  if (csv) {
    write_input("list.csv", data, size);
  } else {
    const std::size_t length = std::min<std::size_t>(data[0] | (data[1] << 8), size - 2);
    write_input("list.offsets.npy", data + 2, length);
    write_input("list.indices.npy", data + 2 + length, size - 2 - length);
  }
  try {
    const horizon::NeighborList list = horizon::read_neighbor_list(prefix, points, half);
    require(list.size() == points, "one row per point");
    require(list.offsets().front() == 0, "offsets start at 0");
    require(static_cast<std::size_t>(list.offsets().back()) == list.indices().size(), "offsets span the indices");
    for (std::size_t i = 0; i < points; ++i) require(list.offsets()[i] <= list.offsets()[i + 1], "rows ascend");
    for (horizon::point_id j : list.indices())
      require(j >= 0 && static_cast<std::size_t>(j) < points, "ids index the points");
  } catch (const horizon::Error&) {
  }
  return 0;
}
