// libFuzzer target: any bytes as a `--bond-filters` JSON file. Accepted or refused with
// horizon::Error; accepted filters must apply: on a small lattice, filtering with the search's
// reach (which skips rows far from every shape) keeps exactly the bonds no filter cuts.
#include "fuzz_input.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"

namespace {

const horizon::PointSet& points() {
  static const horizon::PointSet lattice = horizon::lattice(4, 3, 4.0);  // spacing 1 about (2, 2, 2)
  return lattice;
}

const horizon::NeighborList& bonds() {
  static const horizon::NeighborList list = [] {
    horizon::SearchOptions options;
    options.horizon = 1.5;
    options.threads = 1;
    return horizon::search(points().view(), options);
  }();
  return list;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = horizon::fuzz::write_input("filters.json", data, size);
  std::vector<horizon::BondFilter> filters;
  try {
    filters = horizon::read_bond_filters(path);
  } catch (const horizon::Error&) {
    return 0;
  }
  const auto& list = bonds();
  const auto kept = horizon::filter_bonds(list, points().view(), filters, 1.5, 1);
  std::size_t expected = 0;
  for (std::size_t i = 0; i < list.size(); ++i)
    for (horizon::point_id j : list.row(i)) {
      const std::size_t a = std::min<std::size_t>(i, j), b = std::max<std::size_t>(i, j);
      bool cut = false;
      for (const auto& filter : filters) cut = cut || horizon::cuts(filter, &points().xyz[3 * a], &points().xyz[3 * b]);
      expected += cut ? 0 : 1;
    }
  horizon::fuzz::require(kept.size() == list.size(), "one row per point");
  horizon::fuzz::require(static_cast<std::size_t>(kept.offsets().back()) == expected,
                         "filter_bonds with reach keeps exactly the uncut bonds");
  return 0;
}
