#pragma once
// The subcommands of the horizon CLI; each registers its options and a callback on `app`.
#include <CLI/CLI.hpp>
#include <string>

#include "horizon/points.hpp"

namespace horizon::cli {

void add_generate(CLI::App& app);
void add_search(CLI::App& app);
void add_verify(CLI::App& app);

/// Thrown by verify when the list differs from the oracle: exit status 1.
struct VerifyFailed {};

/// Points from a file, or a built-in problem: `lattice:N` (N^3 points, side 10).
PointSet load_input(const std::string& input);

/// Progress lines on stderr, only when it is a terminal and not --quiet.
class Progress {
public:
  explicit Progress(bool quiet);
  void say(const std::string& what) const;

private:
  bool on_;
};

}  // namespace horizon::cli
