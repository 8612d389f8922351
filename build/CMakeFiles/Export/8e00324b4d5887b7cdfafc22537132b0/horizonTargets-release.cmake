#----------------------------------------------------------------
# Generated CMake target import file for configuration "Release".
#----------------------------------------------------------------

# Commands may need to know the format version.
set(CMAKE_IMPORT_FILE_VERSION 1)

# Import target "horizon::horizon" for configuration "Release"
set_property(TARGET horizon::horizon APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(horizon::horizon PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libhorizon.a"
  )

list(APPEND _cmake_import_check_targets horizon::horizon )
list(APPEND _cmake_import_check_files_for_horizon::horizon "${_IMPORT_PREFIX}/lib/libhorizon.a" )

# Import target "horizon::horizon_cli" for configuration "Release"
set_property(TARGET horizon::horizon_cli APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(horizon::horizon_cli PROPERTIES
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/bin/horizon"
  )

list(APPEND _cmake_import_check_targets horizon::horizon_cli )
list(APPEND _cmake_import_check_files_for_horizon::horizon_cli "${_IMPORT_PREFIX}/bin/horizon" )

# Commands beyond this point should not need to know the version.
set(CMAKE_IMPORT_FILE_VERSION)
