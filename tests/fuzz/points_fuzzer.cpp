// libFuzzer target: any bytes as a points file, read as POINTS_FILE (CMake builds it twice:
// "points.npy" for fuzz_npy_points, "points.txt" for fuzz_text_points: x y [z], CSV, XYZ,
// Peridigm's five columns). Accepted or refused with horizon::Error; anything else (another
// exception, a crash, a sanitizer report) is a defect.
#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "points_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = horizon::fuzz::write_input(POINTS_FILE, data, size);
  try {
    const horizon::PointSet points = horizon::read_points(path);
    horizon::fuzz::check_points(points);
    horizon::fuzz::require(points.blocks.empty() || points.blocks.size() == points.size(), "a block per point");
  } catch (const horizon::Error&) {
  }
  return 0;
}
