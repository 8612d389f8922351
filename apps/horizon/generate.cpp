// horizon generate lattice|random|clusters: the benchmark problems, written to a file.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/io.hpp"

namespace horizon::cli {

namespace {

struct GenerateArgs {
  int n = 10, dims = 3, clusters = 8;
  std::size_t count = 1000;
  double side = 10.0, sigma = 0.5;
  std::uint64_t seed = 1;
  std::string out;
};

CLI::App* add_common(CLI::App& parent, const std::string& name, const std::string& what,
                     GenerateArgs& args) {
  CLI::App* sub = parent.add_subcommand(name, what);
  sub->add_option("--dims", args.dims, "2 or 3")->check(CLI::IsMember({2, 3}));
  sub->add_option("--side", args.side, "side of the cube")->check(CLI::PositiveNumber);
  sub->add_option("--out", args.out, "output file: .npy, .csv or .xyz")->required();
  return sub;
}

}  // namespace

void add_generate(CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* generate = app.add_subcommand("generate", "write a benchmark point set");
  generate->require_subcommand(1);

  CLI::App* grid = add_common(*generate, "lattice", "n^dims points on a cubic lattice", *args);
  grid->add_option("--n", args->n, "points per side")->required()->check(CLI::Range(1, 100000));
  grid->callback([args] { write_points(args->out, lattice(args->n, args->dims, args->side)); });

  CLI::App* random = add_common(*generate, "random", "uniform random points in the cube", *args);
  random->add_option("--count", args->count, "number of points")->required();
  random->add_option("--seed", args->seed, "random seed");
  random->callback([args] {
    write_points(args->out, random_cloud(args->count, args->dims, args->seed, args->side));
  });

  CLI::App* blobs = add_common(*generate, "clusters", "points in Gaussian clusters", *args);
  blobs->add_option("--count", args->count, "number of points")->required();
  blobs->add_option("--clusters", args->clusters, "number of clusters")->required()->check(CLI::PositiveNumber);
  blobs->add_option("--sigma", args->sigma, "standard deviation of each cluster")->required()->check(CLI::PositiveNumber);
  blobs->add_option("--seed", args->seed, "random seed");
  blobs->callback([args] {
    write_points(args->out, clustered_cloud(args->count, args->clusters, args->sigma, args->dims,
                                            args->seed, args->side));
  });
}

}  // namespace horizon::cli
