#pragma once
// The subcommands of the horizon CLI; each registers its options and a callback on `app`.
#include <CLI/CLI.hpp>
#include <string>

#include "horizon/io.hpp"
#include "horizon/points.hpp"
#include "horizon/search.hpp"

namespace horizon::cli {

void add_generate(CLI::App& app);
void add_search(CLI::App& app);
void add_verify(CLI::App& app);

struct SearchArgs {
  std::string input, out, backend = "auto", metric = "l2", format = "npy";
  std::string exchange, decomposition = "rcb", writer = "auto";  // distributed runs only
  std::string gpus;                             // cuda: "all", a count, or a list of devices
  std::string max_memory;                       // e.g. 8G, 512M; empty: what is available
  std::string gpu_max_memory;                   // the same for the GPU; empty: what is free
  std::string box;                              // periodic box "Lx,Ly[,Lz]", 0: open axis
  std::string queries;                          // query points; the input is then the references
  std::string vtk;                              // ParaView file (.vtu) of the points
  std::string bond_filters;                     // JSON file of rectangles and disks that cut bonds
  std::string blocks, block_pairs;              // a block id per point; the block pairs that bond
  std::string radii, radius_rule = "gather";    // a radius per point, and how a pair combines two
  std::string cell, pbc;                        // a periodic cell "ax ay az bx by bz cx cy cz", its pbc "1,1,0"
  std::string outputs;                          // per-entry geometry: letters of S, d, D ("d,D,S")
  double horizon = 0;
  int threads = 0, cells_per_horizon = 1, device = 0;
  bool half = false, unsorted = false, json = false, quiet = false, vtk_bonds = false;
  bool self_interaction = false;
};
/// The options of `args`; `file_cell` (a structure file's cell and pbc) unless --cell says otherwise.
SearchOptions search_options(const SearchArgs& args, const Cell& file_cell = {});
/// Throws when an output would overwrite the input.
void check_output(const SearchArgs& args);

/// Under mpirun (or with --exchange): the distributed search, written by rank 0.
bool distributed_requested(const SearchArgs& args);
void run_distributed(const SearchArgs& args);

/// Thrown by verify when the list differs from the oracle: exit status 1.
struct VerifyFailed {};

/// Points from a file, or a built-in problem: `lattice:N` (N^3 points, side 10).
PointSet load_input(const std::string& input);
/// Points, and the cell and pbc of an atomistic structure file (extended XYZ, LAMMPS data).
Structure load_structure(const std::string& input);

/// Progress lines on stderr, only when it is a terminal and not --quiet.
class Progress {
public:
  explicit Progress(bool quiet);
  void say(const std::string& what) const;

private:
  bool on_;
};

}  // namespace horizon::cli
