// libFuzzer target: any bytes as a text points file (x y [z], CSV, XYZ, Peridigm's five columns).
// Accepted or refused with horizon::Error; anything else is a defect.
#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "points_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = horizon::fuzz::write_input("points.txt", data, size);
  try {
    horizon::fuzz::check_points(horizon::read_points(path));
  } catch (const horizon::Error&) {
  }
  return 0;
}
