
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/apps/horizon/generate.cpp" "apps/horizon/CMakeFiles/horizon_cli.dir/generate.cpp.o" "gcc" "apps/horizon/CMakeFiles/horizon_cli.dir/generate.cpp.o.d"
  "/work/main/apps/horizon/main.cpp" "apps/horizon/CMakeFiles/horizon_cli.dir/main.cpp.o" "gcc" "apps/horizon/CMakeFiles/horizon_cli.dir/main.cpp.o.d"
  "/work/main/apps/horizon/search.cpp" "apps/horizon/CMakeFiles/horizon_cli.dir/search.cpp.o" "gcc" "apps/horizon/CMakeFiles/horizon_cli.dir/search.cpp.o.d"
  "/work/main/apps/horizon/verify.cpp" "apps/horizon/CMakeFiles/horizon_cli.dir/verify.cpp.o" "gcc" "apps/horizon/CMakeFiles/horizon_cli.dir/verify.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build/src/CMakeFiles/horizon.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
