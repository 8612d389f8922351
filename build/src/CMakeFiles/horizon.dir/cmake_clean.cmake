file(REMOVE_RECURSE
  "CMakeFiles/horizon.dir/backends/cuda_absent.cpp.o"
  "CMakeFiles/horizon.dir/backends/cuda_absent.cpp.o.d"
  "CMakeFiles/horizon.dir/backends/openmp.cpp.o"
  "CMakeFiles/horizon.dir/backends/openmp.cpp.o.d"
  "CMakeFiles/horizon.dir/backends/serial.cpp.o"
  "CMakeFiles/horizon.dir/backends/serial.cpp.o.d"
  "CMakeFiles/horizon.dir/core/cell_index.cpp.o"
  "CMakeFiles/horizon.dir/core/cell_index.cpp.o.d"
  "CMakeFiles/horizon.dir/core/family_search.cpp.o"
  "CMakeFiles/horizon.dir/core/family_search.cpp.o.d"
  "CMakeFiles/horizon.dir/core/generate.cpp.o"
  "CMakeFiles/horizon.dir/core/generate.cpp.o.d"
  "CMakeFiles/horizon.dir/core/grid.cpp.o"
  "CMakeFiles/horizon.dir/core/grid.cpp.o.d"
  "CMakeFiles/horizon.dir/core/oracle.cpp.o"
  "CMakeFiles/horizon.dir/core/oracle.cpp.o.d"
  "CMakeFiles/horizon.dir/core/points.cpp.o"
  "CMakeFiles/horizon.dir/core/points.cpp.o.d"
  "CMakeFiles/horizon.dir/core/search.cpp.o"
  "CMakeFiles/horizon.dir/core/search.cpp.o.d"
  "CMakeFiles/horizon.dir/io/atomic_file.cpp.o"
  "CMakeFiles/horizon.dir/io/atomic_file.cpp.o.d"
  "CMakeFiles/horizon.dir/io/list_io.cpp.o"
  "CMakeFiles/horizon.dir/io/list_io.cpp.o.d"
  "CMakeFiles/horizon.dir/io/npy.cpp.o"
  "CMakeFiles/horizon.dir/io/npy.cpp.o.d"
  "CMakeFiles/horizon.dir/io/points_io.cpp.o"
  "CMakeFiles/horizon.dir/io/points_io.cpp.o.d"
  "libhorizon.a"
  "libhorizon.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/horizon.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
