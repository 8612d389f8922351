// libFuzzer target: any bytes as an atomistic structure file, read as STRUCTURE_FILE (CMake
// builds it twice: "structure.extxyz" for fuzz_extxyz, "data.structure" for fuzz_lammps_data).
// Accepted or refused with horizon::Error; anything else (another exception, a crash, a
// sanitizer report) is a defect.
#include <cmath>

#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "points_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = horizon::fuzz::write_input(STRUCTURE_FILE, data, size);
  try {
    const horizon::Structure structure = horizon::read_structure(path);
    horizon::fuzz::check_points(structure.points);
    horizon::fuzz::require(structure.points.dims == 3, "atoms are 3-D");
    for (const auto& vector : structure.cell.vectors)
      for (const double x : vector) horizon::fuzz::require(std::isfinite(x), "a finite cell");
  } catch (const horizon::Error&) {
  }
  return 0;
}
