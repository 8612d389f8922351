// horizon verify: compare a written neighbour list with the brute-force oracle.
#include <algorithm>
#include <iostream>
#include <memory>
#include <random>

#include "commands.hpp"
#include "horizon/grid.hpp"
#include "horizon/io.hpp"
#include "horizon/oracle.hpp"

namespace horizon::cli {

namespace {

struct VerifyArgs {
  std::string input, prefix, metric = "l2";
  double horizon = 0;
  bool half = false, quiet = false;
  std::size_t exact_limit = 20000, sample = 10000;
};

// Rows to check: all of them for small inputs, else a fixed random sample.
std::vector<std::size_t> rows_to_check(std::size_t points, const VerifyArgs& args) {
  std::vector<std::size_t> rows(points);
  for (std::size_t i = 0; i < points; ++i) rows[i] = i;
  if (points <= args.exact_limit) return rows;
  std::mt19937_64 rng(12345);
  for (std::size_t s = 0; s < args.sample; ++s)
    std::swap(rows[s], rows[s + rng() % (points - s)]);
  rows.resize(args.sample);
  std::sort(rows.begin(), rows.end());
  return rows;
}

void run_verify(const VerifyArgs& args) {
  const Progress progress(args.quiet);
  const PointSet points = load_input(args.input);
  validate(points.view());
  SearchOptions options;
  options.horizon = args.horizon;
  options.metric = parse_metric(args.metric);
  options.half = args.half;
  validate_horizon(options.horizon, 1);
  const NeighborList list = read_neighbor_list(args.prefix, points.size(), args.half);
  const auto rows = rows_to_check(points.size(), args);
  progress.say("checking " + std::to_string(rows.size()) + " families against the oracle");

  std::vector<std::string> problems(rows.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::size_t i = rows[r];
    const auto expected = brute_force_family(points.view(), i, options);
    const auto got = list.row(i);
    if (!std::equal(expected.begin(), expected.end(), got.begin(), got.end()))
      problems[r] = "row " + std::to_string(i) + ": " + std::to_string(got.size()) +
                    " neighbours listed, oracle has " + std::to_string(expected.size());
  }
  std::size_t bad = 0;
  for (const auto& p : problems)
    if (!p.empty() && bad++ < 10) std::cout << "MISMATCH " << p << "\n";
  const std::string scope = rows.size() == points.size()
                                ? "all " + std::to_string(rows.size()) + " rows (exact)"
                                : std::to_string(rows.size()) + " sampled rows of " + std::to_string(points.size());
  if (bad) {
    std::cout << "FAIL: " << bad << " of " << scope << " differ from the oracle\n";
    throw VerifyFailed();
  }
  std::cout << "OK: " << scope << " identical to the brute-force oracle\n";
}

}  // namespace

void add_verify(CLI::App& app) {
  auto args = std::make_shared<VerifyArgs>();
  CLI::App* cmd = app.add_subcommand("verify", "compare a neighbour list with the brute-force oracle");
  cmd->add_option("input", args->input, "the points searched")->required();
  cmd->add_option("prefix", args->prefix, "the list's output prefix")->required();
  cmd->add_option("--horizon", args->horizon, "the horizon searched with")->required();
  cmd->add_option("--metric", args->metric, "l2, l1 or linf")->check(CLI::IsMember({"l2", "l1", "linf"}));
  cmd->add_flag("--half", args->half, "the list is a half list");
  cmd->add_option("--exact-limit", args->exact_limit, "check every row up to this many points");
  cmd->add_option("--sample", args->sample, "rows sampled above the exact limit");
  cmd->add_flag("--quiet", args->quiet, "no progress on stderr");
  cmd->callback([args] { run_verify(*args); });
}

}  // namespace horizon::cli
