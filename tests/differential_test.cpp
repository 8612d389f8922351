// Differential random testing: small problems drawn from a fixed seed, each solved by every
// backend built here and by the brute-force oracle, which must agree exactly. The draws aim at
// what nobody writes down: duplicates, collinear and coplanar points, coordinates on exact
// multiples of the horizon and of the cell side, offsets up to 10^12, float32 input, horizons
// from tiny to larger than the cloud, every metric, k = 1-3, full and half lists, queries,
// periodic boxes.
// Every problem is also built in batches of rows (search_in_batches). HORIZON_DIFFERENTIAL_PROBLEMS
// sets the count (default 1000), HORIZON_DIFFERENTIAL_SEED the seed (to run shards in parallel).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "assemble_batches.hpp"
#include "random_problems.hpp"
#include "horizon/oracle.hpp"
#include "horizon/search.hpp"

namespace horizon::testing {
namespace {

TEST(Differential, EveryBackendAgreesWithTheOracleOnRandomProblems) {
  std::vector<Backend> backends{Backend::serial, Backend::openmp};
  if (backend_available(Backend::cuda)) backends.push_back(Backend::cuda);
  std::mt19937_64 rng(seed());
  int compared = 0;
  for (int n = 0; n < problem_count(); ++n) {
    const Problem p = draw(rng);
    const std::size_t count = p.xyz.size() / static_cast<std::size_t>(p.dims);
    std::vector<float> single(p.xyz.begin(), p.xyz.end());
    const PointView view = p.single ? PointView(single.data(), count, p.dims) : PointView(p.xyz.data(), count, p.dims);
    const NeighborList expected = brute_force(PointView(p.xyz.data(), count, p.dims), p.options);
    for (Backend backend : backends) {
      SearchOptions options = p.options;
      options.backend = backend;
      ASSERT_EQ(search(view, options), expected) << "problem " << n << " of seed " << seed() << " (" << p.describe() << "), backend "
                                                 << backend_name(backend);
      ++compared;
    }
    if (p.options.box[0] > 0 || p.options.box[1] > 0 || p.options.box[2] > 0) continue;  // batches: open boxes only
    const std::int64_t batch_entries = 1 + expected.total() / (2 + n % 7);  // 2 to 8 batches
    ASSERT_EQ(assemble_batches(view, p.options, batch_entries), expected)
        << "problem " << n << " (" << p.describe() << "), in batches of " << batch_entries;
  }
  EXPECT_EQ(compared, static_cast<int>(backends.size()) * problem_count());
  std::string names;
  for (Backend backend : backends) names += std::string(" ") + backend_name(backend);
  std::printf("compared %d problems of seed %llu with the oracle on%s and in batches\n", problem_count(),
              static_cast<unsigned long long>(seed()), names.c_str());
}

}  // namespace
}  // namespace horizon::testing
