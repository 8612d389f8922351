file(REMOVE_RECURSE
  "../../bin/horizon"
  "../../bin/horizon.pdb"
  "CMakeFiles/horizon_cli.dir/generate.cpp.o"
  "CMakeFiles/horizon_cli.dir/generate.cpp.o.d"
  "CMakeFiles/horizon_cli.dir/main.cpp.o"
  "CMakeFiles/horizon_cli.dir/main.cpp.o.d"
  "CMakeFiles/horizon_cli.dir/search.cpp.o"
  "CMakeFiles/horizon_cli.dir/search.cpp.o.d"
  "CMakeFiles/horizon_cli.dir/verify.cpp.o"
  "CMakeFiles/horizon_cli.dir/verify.cpp.o.d"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/horizon_cli.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
