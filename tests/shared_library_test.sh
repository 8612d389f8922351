#!/usr/bin/env bash
# libhorizon.so: SONAME libhorizon.so.1; it exports the C API (horizon_*) and namespace horizon
# (with its exceptions' typeinfo and vtables) and nothing else: no horizon::detail beyond the
# allocation functions buffer.hpp calls inline, no highway, no standard-library templates. The
# CLI linked against it writes the same files as the static CLI.
# Usage: shared_library_test.sh LIBRARY STATIC_CLI SHARED_CLI WORK
set -euo pipefail
library=$1 static_cli=$2 shared_cli=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
soname=$(objdump -p "$library" | awk '$1 == "SONAME" {print $2}')
[ "$soname" = libhorizon.so.1 ] || { echo "SONAME is '$soname', expected libhorizon.so.1"; exit 1; }
nm -D --defined-only -C "$library" | cut -d' ' -f3- | sed 's/@@HORIZON_1$//' | sort -u > "$work/exports.txt"
allowed='^(horizon_[a-z_]+|horizon::.*|(typeinfo|typeinfo name|vtable) for horizon::.*|HORIZON_1)$'
inline_helpers='^horizon::detail::(allocate_large|release_large|allocate_scratch|release_scratch)\('
stray=$(grep -v -E "$allowed" "$work/exports.txt" || true)
detail=$(grep '^horizon::detail::' "$work/exports.txt" | grep -v -E "$inline_helpers" || true)
if [ -n "$stray$detail" ]; then
  echo "libhorizon.so exports symbols outside its API:"; printf '%s\n%s\n' "$stray" "$detail" | head -20; exit 1
fi
for symbol in horizon_search horizon_search_radii horizon_search_queries horizon_search_device horizon_list_free \
              horizon_verlet_refresh horizon_last_error horizon_version 'horizon::search(' 'horizon::version()'; do
  grep -qF "$symbol" "$work/exports.txt" || { echo "libhorizon.so does not export $symbol"; exit 1; }
done
# grep reads all of ldd's output: with -q it could stop early and pipefail took ldd's SIGPIPE for a failure.
ldd "$shared_cli" | grep 'libhorizon.so.1 =>' > /dev/null || { echo "$shared_cli is not linked to libhorizon.so.1"; exit 1; }
"$static_cli" search lattice:20 --horizon 1.5075 --out "$work/static" --quiet
"$shared_cli" search lattice:20 --horizon 1.5075 --out "$work/shared" --quiet
cmp "$work/static.offsets.npy" "$work/shared.offsets.npy" && cmp "$work/static.indices.npy" "$work/shared.indices.npy"
echo "libhorizon.so.1: $(wc -l < "$work/exports.txt") exports, all API; the CLI on it writes the static CLI's files"
