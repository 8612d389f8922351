// libFuzzer target: any bytes as a points `.npy` file. Accepted or refused with horizon::Error;
// anything else (another exception, a crash, a sanitizer report) is a defect.
#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "points_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = horizon::fuzz::write_input("points.npy", data, size);
  try {
    horizon::fuzz::check_points(horizon::read_points(path));
  } catch (const horizon::Error&) {
  }
  return 0;
}
