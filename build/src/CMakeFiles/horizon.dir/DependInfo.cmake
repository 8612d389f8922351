
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/src/backends/cuda_absent.cpp" "src/CMakeFiles/horizon.dir/backends/cuda_absent.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/backends/cuda_absent.cpp.o.d"
  "/work/main/src/backends/openmp.cpp" "src/CMakeFiles/horizon.dir/backends/openmp.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/backends/openmp.cpp.o.d"
  "/work/main/src/backends/serial.cpp" "src/CMakeFiles/horizon.dir/backends/serial.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/backends/serial.cpp.o.d"
  "/work/main/src/core/cell_index.cpp" "src/CMakeFiles/horizon.dir/core/cell_index.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/core/cell_index.cpp.o.d"
  "/work/main/src/core/family_search.cpp" "src/CMakeFiles/horizon.dir/core/family_search.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/core/family_search.cpp.o.d"
  "/work/main/src/core/generate.cpp" "src/CMakeFiles/horizon.dir/core/generate.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/core/generate.cpp.o.d"
  "/work/main/src/core/grid.cpp" "src/CMakeFiles/horizon.dir/core/grid.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/core/grid.cpp.o.d"
  "/work/main/src/core/oracle.cpp" "src/CMakeFiles/horizon.dir/core/oracle.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/core/oracle.cpp.o.d"
  "/work/main/src/core/points.cpp" "src/CMakeFiles/horizon.dir/core/points.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/core/points.cpp.o.d"
  "/work/main/src/core/search.cpp" "src/CMakeFiles/horizon.dir/core/search.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/core/search.cpp.o.d"
  "/work/main/src/io/atomic_file.cpp" "src/CMakeFiles/horizon.dir/io/atomic_file.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/io/atomic_file.cpp.o.d"
  "/work/main/src/io/list_io.cpp" "src/CMakeFiles/horizon.dir/io/list_io.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/io/list_io.cpp.o.d"
  "/work/main/src/io/npy.cpp" "src/CMakeFiles/horizon.dir/io/npy.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/io/npy.cpp.o.d"
  "/work/main/src/io/points_io.cpp" "src/CMakeFiles/horizon.dir/io/points_io.cpp.o" "gcc" "src/CMakeFiles/horizon.dir/io/points_io.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
