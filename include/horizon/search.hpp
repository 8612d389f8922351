#pragma once
/// \file search.hpp
/// The entry point: all-pairs fixed-radius neighbour search of one point set against itself.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "horizon/cell.hpp"
#include "horizon/metric.hpp"
#include "horizon/neighbor_list.hpp"
#include "horizon/points.hpp"

namespace horizon {

/// Execution strategies of one algorithm; all return the same list bit for bit.
enum class Backend {
  automatic,  ///< the fastest one built and usable here
  serial,     ///< the readable reference
  openmp,     ///< all cores of one node
  cuda,       ///< one GPU (when built with CUDA)
};
Backend parse_backend(const std::string& name);
const char* backend_name(Backend backend);
/// Whether `backend` is compiled in and has hardware to run on.
bool backend_available(Backend backend);
/// The SIMD instruction set the CPU backends chose for this CPU at run time ("AVX3", "AVX2", ...).
const char* cpu_simd_target();

struct SearchOptions {
  double horizon = 0;                 ///< pairs closer than this (strictly) are neighbours
  Metric metric = Metric::euclidean;
  int cells_per_horizon = 1;          ///< k: cell side horizon/k, stencil of 2k+1 cells per axis
  bool half = false;                  ///< keep each pair once, in the row of the smaller id
  bool sort_rows = true;              ///< sort each family by id (false: any order, faster)
  Backend backend = Backend::automatic;
  int threads = 0;                    ///< openmp threads; 0 = all cores
  int device = 0;                     ///< cuda device
  /// Only points 0 .. queries-1 get families (0: all); the others are searched but get empty
  /// rows. The distributed layer puts its owned points first and its ghosts after.
  std::size_t queries = 0;
  /// cuda host API: most list entries on the GPU at once (0: as fit). A longer list goes in
  /// batches of rows, two at a time (one filling while the other is copied back), each up to half.
  std::int64_t gpu_batch_entries = 0;
  /// cuda: GPU memory, in bytes, a search sizes its list, hit bits and batches to (0: what is
  /// free), for a solver that keeps its own arrays on the same GPU.
  std::size_t gpu_max_memory = 0;
  /// Host memory the list may take, in bytes (0: what the system reports available). Checked
  /// once the count pass knows the list's size, before it is allocated: ListTooLarge.
  std::size_t max_memory = 0;
  /// cuda: the GPUs of one search (empty: `device` alone). With several, the points are cut
  /// into as many parts of equal point count (recursive coordinate bisection), each searched
  /// with its horizon-wide halo on its own GPU and host thread, the rows assembled in input order.
  std::vector<int> devices;
  /// Periodic box (scipy's boxsize): box[a] > 0 makes axis a periodic with period box[a], 0
  /// leaves it open. Points must lie in [0, box[a]) and the horizon be < box[a] / 2 on every
  /// periodic axis; the distance is then to the nearest periodic image, each j at most once per
  /// row. Images are points of their own: image coordinates x_j +- box[a] are rounded to double
  /// before the pair test, as the oracle does.
  std::array<double, 3> box{0, 0, 0};
  /// A periodic cell of any shape (cell.hpp), for atomistic systems; exclusive with `box`. Points
  /// may lie anywhere and the horizon may exceed the cell: row i lists every image of every j
  /// within the horizon, each an entry (i, j, S) of its own with its integer shift S, ordered by
  /// j, then S (lexicographically); i with itself at S = 0 only with `self_interaction`. A half
  /// list keeps (i, j, S) with i < j, or i = j and S > 0 (its first non-zero component). The
  /// pair test is the metric's on D = x_j + S . cell - x_i, computed in that order:
  /// D_a = (x_j,a - x_i,a) + ((S_0 c_0a + S_1 c_1a) + S_2 c_2a), the same on every backend.
  Cell cell;
  /// Shifts, distances and vectors per entry (cell.hpp): they put the search on the cell path
  /// (as a cell does; `box` then counts as an orthorhombic cell), even without periodic axes.
  PairOutputs outputs;
  /// With a cell or outputs: point i is its own neighbour at shift 0 (ASE's self_interaction).
  bool self_interaction = false;
};

/// One part of a search over several devices: its device, points and time.
struct PartStats {
  int device = 0;
  std::size_t owned = 0, halo = 0;  ///< points whose rows it built; points it read as references
  std::int64_t entries = 0;         ///< entries of its rows
  /// Its search on its own thread: upload and build (GPU parts copy their rows back during the
  /// assembly, unless their lists did not fit on their GPUs), or the whole host-path search.
  double seconds = 0;
  double build_seconds = 0;         ///< of which the build itself (GPU: kernels; CPU: grid + search)
};

/// Seconds spent in each phase, and what ran.
struct SearchStats {
  Backend backend = Backend::serial;
  int threads = 1;
  /// Why that backend and thread count: "asked for", or what Backend::automatic went by (the
  /// problem's size, the usable CPUs, busy cores, a usable GPU).
  std::string choice;
  double grid_seconds = 0;    ///< bounds, cell coordinates, sort by cell
  double search_seconds = 0;  ///< distance tests and CSR assembly
  // cuda only: the GPU, its peak memory, and the host<->device split of the time.
  std::string gpu_name;
  std::size_t peak_gpu_bytes = 0;
  double host_to_device_seconds = 0;
  double kernel_seconds = 0;
  double device_to_host_seconds = 0;
  /// Several devices: each part, and the time to cut the points and to assemble the rows.
  std::vector<PartStats> parts;
  double partition_seconds = 0, assemble_seconds = 0;
};

/// The neighbour list of `points` against themselves. Throws horizon::Error on NaN/Inf
/// coordinates, a horizon that is not finite and > 0, k outside 1..3, or >= 2^31 points.
NeighborList search(PointView points, const SearchOptions& options, SearchStats* stats = nullptr);

/// Pays now what a first search of `backend` would pay: the thread pool (as many threads as a
/// large problem would take), the SIMD dispatch and, for cuda, the GPU's context, memory pool and
/// streams (automatic: the CPU's and, when one is usable, the GPU's). For callers who want their
/// first step to cost what the others do. Throws horizon::Error for a backend not available here.
void warm_up(Backend backend = Backend::automatic);

/// The families of `queries` among `references` (two point sets of the same dimension): row q
/// holds every reference r with d(q, r) < horizon; nothing is excluded as "self" (a query equal
/// to a reference finds it). Ids index `references`. Throws for half lists and
/// SearchOptions::queries, which are about one point set.
NeighborList search(PointView queries, PointView references, const SearchOptions& options,
                    SearchStats* stats = nullptr);

}  // namespace horizon
