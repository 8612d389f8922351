#!/usr/bin/env bash
# Builds sparse_bench.cpp against two libhorizon.a (NEW, OLD: Release builds of the two trees)
# and runs them alternately, twice (LIBS: more libraries for NEW, e.g. -lcudart for a CUDA build).
# Usage: bash run.sh NEW_BUILD OLD_BUILD [OLD_INCLUDE]
set -e
here=$(dirname "$0")
new=$1 old=$2
g++ -O2 -std=c++20 -fopenmp -Iinclude "$here/sparse_bench.cpp" "$new/src/libhorizon.a" -lhwy ${LIBS:-} -o /tmp/sparse_bench_new
g++ -O2 -std=c++20 -fopenmp -I"${3:-include}" "$here/sparse_bench.cpp" "$old/src/libhorizon.a" -lhwy -o /tmp/sparse_bench_old
for round in 1 2; do
  for tree in new old; do
    echo "# $tree, round $round"
    /tmp/sparse_bench_$tree
  done
done
