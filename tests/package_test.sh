#!/usr/bin/env bash
# Builds the Debian package (CPack), unpacks it into a fresh root, and checks that the package,
# the CLI it installs, its --json and the Python package (when built) give one version, and that
# the installed CLI searches. Usage: package_test.sh BUILD WORK VERSION [PYTHON]
set -euo pipefail
build=$1 work=$2 version=$3 python=${4:-}
rm -rf "$work" && mkdir -p "$work"
(cd "$build" && cpack -G DEB -B "$work/pkg" > "$work/cpack.log") || { cat "$work/cpack.log"; exit 1; }
deb="$work/pkg/horizon_${version}_$(dpkg --print-architecture).deb"
[ -f "$deb" ] || { echo "no $deb; cpack made: $(ls "$work/pkg")"; exit 1; }
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || { echo "package version $(dpkg-deb -f "$deb" Version) != $version"; exit 1; }
dpkg -x "$deb" "$work/root"
for f in usr/bin/horizon usr/include/horizon/search.hpp usr/include/horizon/version.hpp \
         "usr/lib*/cmake/horizon/horizonConfigVersion.cmake" "usr/lib*/libhorizon.so.1" "usr/lib*/pkgconfig/horizon.pc" \
         usr/include/horizon/horizon.h usr/share/doc/horizon/copyright; do
  compgen -G "$work/root/$f" > /dev/null || { echo "missing from the package: /$f"; exit 1; }
done
cli="$work/root/usr/bin/horizon"
[ "$("$cli" --version)" = "horizon $version" ] || { echo "horizon --version: $("$cli" --version)"; exit 1; }
json=$("$cli" search lattice:10 --horizon 1.5 --json --quiet)
echo "$json" | grep -q "\"version\":\"$version\"" || { echo "--json lacks the version: $json"; exit 1; }
echo "$json" | grep -q '"neighbors":15120' || { echo "wrong list: $json"; exit 1; }
if [ -n "$python" ] && [ -d "$build/python/horizon" ]; then
  PYTHONPATH="$build/python" "$python" -c "import horizon, sys; sys.exit(horizon.__version__ != '$version')" \
    || { echo "horizon.__version__ differs from $version"; exit 1; }
fi
echo "horizon_${version}: package, CLI, --json and Python agree; the installed CLI searches"
