// horizon search under mpirun: every rank reads the input, keeps its block (thesis, halo) or
// everything (overlap), and the files of a serial run are written either by rank 0 after a
// gather (it then needs the memory of the whole list) or by every rank at once into the shared
// files (write_rows_parallel): --writer, by default the gather unless rank 0 cannot hold the list.
#include <mpi.h>

#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "horizon/block_filter.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/cuda.hpp"
#include "horizon/distributed.hpp"
#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "horizon/stopwatch.hpp"
#include "horizon/version.hpp"

namespace horizon::cli {

bool distributed_requested(const SearchArgs& args) {
  int initialized = 0, size = 1;
  MPI_Initialized(&initialized);
  if (!initialized) return false;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size > 1 || !args.exchange.empty();
}

/// One rank per GPU: the ranks of a node take its GPUs (--gpus, else all visible) in turn by
/// node-local rank.
void bind_rank_to_gpu(SearchOptions& options) {
  const bool cuda = options.backend == Backend::cuda ||
                    (options.backend == Backend::automatic && backend_available(Backend::cuda));
  if (!cuda) return;
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int local = 0;
  MPI_Comm_rank(node, &local);
  MPI_Comm_free(&node);
  std::vector<int> devices = options.devices;
  for (int d = 0; devices.empty() && d < cuda_device_count(); ++d) devices.push_back(d);
  if (!devices.empty()) options.device = devices[static_cast<std::size_t>(local) % devices.size()];
  options.devices.clear();
}

/// The writer for a list of `entries` (the same on every rank). The gather is the default: on
/// one node's disk it was as fast or faster at 1-16 ranks (bench/results/mpi_writer_*); the
/// parallel writer is for lists rank 0 cannot hold.
bool write_in_parallel(const SearchArgs& args, std::int64_t entries, const SearchOptions& options) {
  if (args.format == "csv") {
    if (args.writer == "parallel") throw Error("--writer parallel writes .npy files only (not --format csv)");
    return false;
  }
  if (args.writer != "auto") return args.writer == "parallel";
  return !gather_fits(MPI_COMM_WORLD, entries, options);
}

void run_distributed(const SearchArgs& args) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  check_output(args);
  if (!args.block_pairs.empty() && !args.queries.empty())
    throw Error("--block-pairs with --queries: not supported (the blocks are the input's points')");
  if (!args.box.empty() && !args.bond_filters.empty())
    throw Error("--bond-filters with --box: bonds across the periodic faces have no single segment; not supported");
  if (args.writer == "parallel" && (!args.vtk.empty() || !args.bond_filters.empty() || !args.block_pairs.empty()))
    throw Error("--vtk, --bond-filters and --block-pairs need the whole list on rank 0: use --writer gather (or auto)");
  const Progress progress(args.quiet || rank != 0);
  Stopwatch clock;
  Structure structure = load_structure(args.input);  // points, and an atomistic file's cell
  PointSet& all = structure.points;
  if (!args.blocks.empty()) all.blocks = read_blocks(args.blocks, all.size());
  const PointSet queries = args.queries.empty() ? PointSet{} : load_input(args.queries);
  const PointSet& row_points = args.queries.empty() ? all : queries;  // the rows
  const std::vector<double> radii =
      args.radii.empty() ? std::vector<double>{}
                         : read_radii(args.radii, row_points.size(), args.queries.empty() ? "points" : "queries");
  const RadiusRule radius_rule = parse_radius_rule(args.radius_rule);
  if (!radii.empty() && !args.queries.empty() && radius_rule != RadiusRule::gather)
    throw Error(std::string("--radii with --queries: only --radius-rule gather (each query's own radius), not ") +
                radius_rule_name(radius_rule));
  // Every rank reads the filters, so bad ones are refused before the search, by all ranks alike.
  const std::vector<BondFilter> filters =
      args.bond_filters.empty() ? std::vector<BondFilter>{} : read_bond_filters(args.bond_filters);
  const BlockPairs block_pairs = args.block_pairs.empty() ? BlockPairs{} : BlockPairs::parse(args.block_pairs);
  if (!args.block_pairs.empty() && all.blocks.empty())
    throw Error("--block-pairs needs a block per point: --blocks FILE, or a Peridigm input (x y z block volume)");
  if (!block_pairs.pairs.empty())  // the pairs checked against the blocks on every rank (a list without bonds)
    filter_blocks(NeighborList(Buffer<std::int64_t>(all.size() + 1, 0), {}, false), all.blocks, block_pairs, 1);
  const bool on_rank0 = !args.vtk.empty() || !filters.empty() || !block_pairs.pairs.empty();  // whole list needed
  const double read_seconds = clock.lap();

  DistributedOptions options;
  options.search = search_options(args, structure.cell);
  if ((!filters.empty() || !block_pairs.pairs.empty()) && options.search.outputs.any())
    throw Error("--outputs with --bond-filters or --block-pairs: not supported (the filters keep ids only)");
  if (args.format == "csv" && options.search.outputs.any())
    throw Error(args.out + ": shifts, distances and vectors are written as .npy files, not csv");
  if (!filters.empty() && options.search.cell.periodic())
    throw Error("--bond-filters with --cell: bonds across the periodic faces have no single segment; not supported");
  for (const double r : radii) options.search.horizon = std::max(options.search.horizon, r);  // the filters' reach
  bind_rank_to_gpu(options.search);
  options.exchange = parse_exchange(args.exchange.empty() ? "halo" : args.exchange);
  options.decomposition = args.decomposition == "brick" ? Decomposition::Kind::brick : Decomposition::Kind::rcb;
  const std::size_t n = row_points.size();
  // This rank's share [first, last) of `count` points: a block of the input, or all (overlap).
  const bool overlap = options.exchange == Exchange::overlap;
  const auto share = [&](std::size_t count) {
    const auto r = static_cast<std::size_t>(rank), p = static_cast<std::size_t>(size);
    return overlap ? std::pair<std::size_t, std::size_t>{0, count} : std::pair{count * r / p, count * (r + 1) / p};
  };
  // The points of this rank's share, and their global ids (none with overlap: all are held).
  const auto held_part = [&](const PointSet& set, std::vector<std::int64_t>& ids) {
    const auto [first, last] = share(set.size());
    if (!overlap)
      for (std::size_t i = first; i < last; ++i) ids.push_back(static_cast<std::int64_t>(i));
    return PointSet{set.dims, {set.xyz.begin() + static_cast<std::ptrdiff_t>(first * set.dims),
                               set.xyz.begin() + static_cast<std::ptrdiff_t>(last * set.dims)}};
  };
  std::vector<std::int64_t> ids, reference_ids;
  const PointSet held = held_part(row_points, ids);
  const auto [first_radius, last_radius] = share(radii.size());
  const std::vector<double> held_radii(radii.begin() + static_cast<std::ptrdiff_t>(first_radius),
                                       radii.begin() + static_cast<std::ptrdiff_t>(last_radius));
  progress.say("searching " + std::to_string(n) + " points on " + std::to_string(size) + " ranks");
  DistributedStats stats;
  OwnedRows rows;
  if (!args.queries.empty()) {
    const PointSet held_references = held_part(all, reference_ids);
    rows = search_distributed_queries(MPI_COMM_WORLD, held.view(), ids, n, held_references.view(), reference_ids,
                                      all.size(), options, held_radii, &stats);
  } else {
    rows = radii.empty()
               ? search_distributed(MPI_COMM_WORLD, held.view(), ids, n, options, &stats)
               : search_distributed(MPI_COMM_WORLD, held.view(), ids, held_radii, radius_rule, n, options, &stats);
  }
  clock.lap();
  // Rows travel to rank 0 only when there is a file to write.
  std::string written;
  std::int64_t total = 0;
  const std::int64_t mine = rows.rows.total();
  MPI_Allreduce(&mine, &total, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  const bool parallel = !args.out.empty() && !on_rank0 && write_in_parallel(args, total, options.search);
  const std::int64_t unfiltered = total;
  double filter_seconds = 0;
  if (!args.out.empty() && parallel) {
    written = write_rows_parallel(MPI_COMM_WORLD, rows, n, args.out);
  } else if (!args.out.empty() || on_rank0) {
    NeighborList list = gather_rows(MPI_COMM_WORLD, rows, n, options.search.half);
    stats.gather = clock.lap();
    if (rank == 0) {
      // Filters and ParaView output on rank 0, as a one-node search applies them.
      const double reach = bond_reach(options.search, all.dims);
      if (!filters.empty())
        list = args.queries.empty() ? filter_bonds(std::move(list), all.view(), filters, reach, args.threads)
                                    : filter_bonds(std::move(list), queries.view(), all.view(), filters, reach, args.threads);
      if (!block_pairs.pairs.empty()) list = filter_blocks(std::move(list), all.blocks, block_pairs, args.threads);
      total = list.total();
      filter_seconds = clock.lap();
      if (!args.out.empty())
        written = write_neighbor_list(args.out, list, args.format == "csv" ? ListFormat::csv : ListFormat::npy);
      if (!args.vtk.empty()) {
        write_vtk(args.vtk, row_points, list, args.vtk_bonds, radii);
        written += (written.empty() ? "" : ",") + args.vtk;
      }
    }
  }
  const double write_seconds = clock.lap();
  if (rank != 0) return;
  const double build = stats.preprocess + stats.decompose + stats.communicate + stats.search;
  if (args.json) {
    nlohmann::json report = {
        {"version", version()},
        {"points", n}, {"dims", all.dims}, {"horizon", args.horizon}, {"metric", args.metric},
        {"cells_per_horizon", args.cells_per_horizon}, {"half", args.half}, {"neighbors", total},
        {"backend", args.backend}, {"threads", args.threads}, {"ranks", size},
        {"exchange", exchange_name(options.exchange)}, {"decomposition", args.decomposition},
        {"writer", args.out.empty() ? "none" : parallel ? "parallel" : "gather"},
        {"seconds",
         {{"read", read_seconds}, {"preprocess", stats.preprocess}, {"decompose", stats.decompose},
          {"communicate", stats.communicate}, {"search", stats.search}, {"gather", stats.gather},
          {"filter", filter_seconds}, {"write", write_seconds},
          {"total", read_seconds + build + stats.gather + filter_seconds + write_seconds}}},
        {"bytes_sent", stats.bytes_sent}, {"messages_sent", stats.messages_sent},
        {"max_bytes_sent", stats.max_bytes_sent}, {"max_messages_sent", stats.max_messages_sent},
        {"ghosts", stats.ghosts}, {"owned_min", stats.min_owned}, {"owned_max", stats.max_owned},
        {"points_per_second", build > 0 ? static_cast<double>(n) / build : 0.0}, {"outputs", written}};
    if (!radii.empty()) report["radius_rule"] = radius_rule_name(radius_rule);
    if (!filters.empty()) report["bond_filters"] = filters.size();
    if (!block_pairs.pairs.empty()) report["block_pairs"] = block_pairs.pairs.size();
    if (!filters.empty() || !block_pairs.pairs.empty()) report["bonds_cut"] = unfiltered - total;
    std::cout << report.dump() << std::endl;
  } else {
    std::cout << n << " points on " << size << " ranks (" << exchange_name(options.exchange) << "): "
              << total << " neighbours; communicate " << stats.communicate << " s, search " << stats.search
              << " s, " << stats.bytes_sent << " bytes in " << stats.messages_sent << " messages\n";
    if (!written.empty()) std::cout << "wrote " << written << "\n";
  }
}

}  // namespace horizon::cli
