// horizon search: read points, build the neighbour list, write it, report timings.
#include <array>
#include <cctype>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "horizon/block_filter.hpp"
#include "horizon/bond_filter.hpp"
#include "horizon/cuda.hpp"
#include "horizon/error.hpp"
#include "horizon/io.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"
#include "horizon/stopwatch.hpp"
#include "horizon/version.hpp"

namespace horizon::cli {

namespace {

void run_search(const SearchArgs& args) {
#if defined(HORIZON_WITH_MPI)
  if (distributed_requested(args)) return run_distributed(args);
#endif
  const Progress progress(args.quiet);
  check_output(args);
  Stopwatch clock;
  progress.say("reading " + args.input);
  Structure input = load_structure(args.input);
  PointSet& references = input.points;
  if (!args.blocks.empty()) references.blocks = read_blocks(args.blocks, references.size());
  const PointSet queries = args.queries.empty() ? PointSet{} : load_input(args.queries);
  const PointSet& points = args.queries.empty() ? references : queries;  // the rows
  // one radius per row: per query with --queries
  const std::vector<double> radii = args.radii.empty() ? std::vector<double>{} : read_radii(args.radii, points.size(), args.queries.empty() ? "points" : "queries");
  const double read_seconds = clock.lap();

  SearchOptions options = search_options(args, input.cell);
  const RadiusRule radius_rule = parse_radius_rule(args.radius_rule);
  if (!radii.empty()) {
    if (!args.queries.empty() && radius_rule != RadiusRule::gather)
      throw Error(std::string("--radii with --queries: only --radius-rule gather (each query's own radius), not ") +
                  radius_rule_name(radius_rule));
    for (const double r : radii) options.horizon = std::max(options.horizon, r);  // the filters' reach
  }
  const std::vector<BondFilter> filters =
      args.bond_filters.empty() ? std::vector<BondFilter>{} : read_bond_filters(args.bond_filters);
  if (!filters.empty() && (options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0 || options.cell.periodic()))
    throw Error("--bond-filters with --box or --cell: bonds across the periodic faces have no single segment; not supported");
  if ((!filters.empty() || !args.block_pairs.empty()) && options.outputs.any())
    throw Error("--outputs with --bond-filters or --block-pairs: not supported (the filters keep ids only)");
  const BlockPairs block_pairs = args.block_pairs.empty() ? BlockPairs{} : BlockPairs::parse(args.block_pairs);
  if (!args.block_pairs.empty() && references.blocks.empty())
    throw Error("--block-pairs needs a block per point: --blocks FILE, or a Peridigm input (x y z block volume)");
  if (!args.block_pairs.empty() && !args.queries.empty())
    throw Error("--block-pairs with --queries: not supported (the blocks are the input's points')");
  progress.say("searching " + std::to_string(points.size()) + " points");
  SearchStats stats;
  NeighborList list;
  std::string written;
  std::int64_t streamed = -1;  // entries written in batches, when the list did not fit in memory
  try {
    if (!radii.empty())
      list = args.queries.empty() ? search_with_radii(references.view(), radii, radius_rule, options, &stats)
                                  : search_with_radii(queries.view(), radii, references.view(), options, &stats);
    else
      list = args.queries.empty() ? search(references.view(), options, &stats)
                                  : search(queries.view(), references.view(), options, &stats);
  } catch (const ListTooLarge& too_large) {
    const bool periodic = options.box[0] > 0 || options.box[1] > 0 || options.box[2] > 0 || options.cell.periodic() ||
                          options.outputs.any() || options.self_interaction;
    const bool plain = args.queries.empty() && radii.empty() && filters.empty() && block_pairs.pairs.empty() && args.vtk.empty() && !periodic;
    if (args.out.empty() || args.format != "npy" || !plain) throw;
    // It fits on disk: built again in batches of half the memory allowed, each appended to the files.
    progress.say("the list does not fit in memory: writing it to " + args.out + " in batches, on the CPU");
    SearchOptions cpu = options;
    if (cpu.backend != Backend::serial) cpu.backend = Backend::openmp;
    cpu.devices.clear();
    streamed = write_neighbor_list_in_batches(args.out, references.view(), cpu,
                                              static_cast<std::int64_t>(too_large.bytes_available / 2 / sizeof(point_id)), &stats);
    written = args.out + ".offsets.npy," + args.out + ".indices.npy";
  }
  clock.lap();
  const std::int64_t unfiltered = list.total();
  if (!filters.empty()) {
    progress.say("applying " + std::to_string(filters.size()) + " bond filters");
    const double reach = bond_reach(options, points.dims);
    list = args.queries.empty() ? filter_bonds(std::move(list), references.view(), filters, reach, args.threads)
                                : filter_bonds(std::move(list), queries.view(), references.view(), filters, reach, args.threads);
  }
  if (!block_pairs.pairs.empty()) {
    progress.say("keeping the bonds of " + std::to_string(block_pairs.pairs.size()) + " block pairs");
    list = filter_blocks(std::move(list), references.blocks, block_pairs, args.threads);
  }
  const double filter_seconds = clock.lap();
  const std::int64_t entries = streamed < 0 ? list.total() : streamed;

  if (!args.out.empty() && streamed < 0) {
    progress.say("writing " + std::to_string(list.total()) + " neighbours");
    written = write_neighbor_list(args.out, list, args.format == "csv" ? ListFormat::csv : ListFormat::npy);
  }
  if (!args.vtk.empty()) {
    progress.say("writing " + args.vtk);
    write_vtk(args.vtk, points, list, args.vtk_bonds, radii);
    written += (written.empty() ? "" : ",") + args.vtk;
  }
  const double write_seconds = clock.lap();
  const double build = stats.grid_seconds + stats.search_seconds;
  const double rate = build > 0 ? static_cast<double>(points.size()) / build : 0.0;

  if (args.json) {
    nlohmann::json report = {
        {"version", version()},
        {"points", points.size()},
        {"dims", points.dims},
        {"references", references.size()},
        {"horizon", options.horizon},
        {"metric", metric_name(options.metric)},
        {"cells_per_horizon", options.cells_per_horizon},
        {"half", options.half},
        {"neighbors", entries},
        {"backend", backend_name(stats.backend)},
        {"backend_choice", stats.choice},
        {"threads", stats.threads},
        {"seconds",
         {{"read", read_seconds},
          {"grid", stats.grid_seconds},
          {"search", stats.search_seconds},
          {"filter", filter_seconds},
          {"write", write_seconds},
          {"total", read_seconds + build + filter_seconds + write_seconds}}},
        {"points_per_second", rate},
        {"outputs", written},
    };
    if (streamed >= 0) report["written_in_batches"] = true;
    if (!radii.empty()) report["radius_rule"] = radius_rule_name(radius_rule);
    if (options.cell.periodic()) {
      report["cell"] = options.cell.vectors;
      report["pbc"] = options.cell.pbc;
    }
    if (!filters.empty()) report["bond_filters"] = filters.size();
    if (!block_pairs.pairs.empty()) report["block_pairs"] = block_pairs.pairs.size();
    if (!filters.empty() || !block_pairs.pairs.empty()) report["bonds_cut"] = unfiltered - list.total();
    if (stats.backend == Backend::cuda) {
      report["gpu"] = stats.gpu_name;
      report["peak_gpu_bytes"] = stats.peak_gpu_bytes;
      report["seconds"]["host_to_device"] = stats.host_to_device_seconds;
      report["seconds"]["kernels"] = stats.kernel_seconds;
      report["seconds"]["device_to_host"] = stats.device_to_host_seconds;
    }
    if (!stats.parts.empty()) {  // several GPUs: the balance and each GPU's time
      nlohmann::json parts = nlohmann::json::array();
      double most_points = 0, most_entries = 0;
      for (const PartStats& part : stats.parts) {
        parts.push_back({{"device", part.device}, {"points", part.owned}, {"halo", part.halo},
                         {"entries", part.entries}, {"seconds", part.seconds},
                         {"build_seconds", part.build_seconds}});
        most_points = std::max(most_points, static_cast<double>(part.owned));
        most_entries = std::max(most_entries, static_cast<double>(part.entries));
      }
      const double count = static_cast<double>(stats.parts.size());
      report["gpus"] = parts;
      report["imbalance"] = {
          {"points", most_points / (static_cast<double>(points.size()) / count)},
          {"entries", list.total() > 0 ? most_entries / (static_cast<double>(list.total()) / count) : 1.0}};
      report["seconds"]["partition"] = stats.partition_seconds;
      report["seconds"]["assemble"] = stats.assemble_seconds;
    }
    std::cout << report.dump() << std::endl;
  } else {
    std::cout << points.size() << " points (" << points.dims << "-D), " << (radii.empty() ? "horizon " : "radii up to ")
              << options.horizon << (radii.empty() ? "" : std::string(" (") + radius_rule_name(radius_rule) + ")")
              << ": " << entries << " neighbours (" << (options.half ? "half" : "full")
              << " list, " << static_cast<double>(entries) / std::max<std::size_t>(1, points.size())
              << " per point)\n"
              << "backend " << backend_name(stats.backend) << ", " << stats.threads
              << " thread(s): grid " << stats.grid_seconds << " s, search " << stats.search_seconds
              << " s, " << rate / 1e6 << " M points/s\n";
    if (!written.empty()) std::cout << "wrote " << written << " in " << write_seconds << " s\n";
  }
}

}  // namespace

/// --gpus: "all", a count N (devices 0..N-1), or a comma-separated list of devices.
std::vector<int> parse_gpus(const std::string& gpus) {
  if (gpus.empty()) return {};
  std::vector<int> devices;
  const int visible = cuda_device_count();
  if (gpus == "all") {
    if (visible == 0) throw Error("--gpus all: no CUDA device is visible");
    for (int d = 0; d < visible; ++d) devices.push_back(d);
    return devices;
  }
  const bool list = gpus.find(',') != std::string::npos;
  std::size_t at = 0;
  while (at <= gpus.size()) {
    const std::size_t end = std::min(gpus.find(',', at), gpus.size());
    const std::string item = gpus.substr(at, end - at);
    if (item.empty() || item.find_first_not_of("0123456789") != std::string::npos)
      throw Error("--gpus " + gpus + ": expected all, a count, or a list of devices such as 0,1");
    devices.push_back(std::stoi(item));
    at = end + 1;
  }
  if (!list) {  // a count
    const int count = devices[0];
    if (count < 1) throw Error("--gpus " + gpus + ": the count must be at least 1");
    devices.clear();
    for (int d = 0; d < count; ++d) devices.push_back(d);
  }
  for (int d : devices)
    if (d >= visible)
      throw Error("--gpus " + gpus + ": CUDA device " + std::to_string(d) + " does not exist (" +
                  std::to_string(visible) + " visible)");
  return devices;
}

/// The number `text` starts with, and how many characters it took (0: none).
std::size_t leading_number(const std::string& text, double& value) {
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  return used;
}

/// --box Lx,Ly[,Lz]: the period of each axis, 0 for an open one.
std::array<double, 3> parse_box(const std::string& text) {
  std::array<double, 3> box{0, 0, 0};
  if (text.empty()) return box;
  std::size_t axis = 0, from = 0;
  for (; from <= text.size() && axis < 3; ++axis) {
    const std::size_t comma = std::min(text.find(',', from), text.size());
    const std::string field = text.substr(from, comma - from);
    const std::size_t used = leading_number(field, box[axis]);
    if (used == 0 || used != field.size())
      throw Error("--box " + text + ": '" + field + "' is not a number (expected Lx,Ly[,Lz], 0 for an open axis)");
    from = comma + 1;
  }
  if (axis < 2 || from <= text.size())
    throw Error("--box " + text + ": expected two or three periods Lx,Ly[,Lz] (0 for an open axis)");
  return box;
}

/// --cell "ax ay az bx by bz cx cy cz" (commas or spaces; 4 numbers for a 2-D cell) and --pbc
/// 1,1,0 (default: every axis periodic), over `file_cell` (a structure file's); --outputs letters.
Cell parse_cell(const std::string& text, const std::string& pbc, Cell cell) {
  if (!text.empty()) {
    std::vector<double> values;
    std::string field;
    for (std::size_t at = 0; at <= text.size(); ++at) {
      const bool separator = at == text.size() || text[at] == ',' || std::isspace(static_cast<unsigned char>(text[at]));
      if (!separator) {
        field += text[at];
        continue;
      }
      if (field.empty()) continue;
      double value = 0;
      const std::size_t used = leading_number(field, value);
      if (used == 0 || used != field.size())
        throw Error("--cell: '" + field + "' is not a number (expected \"ax ay az bx by bz cx cy cz\")");
      values.push_back(value);
      field.clear();
    }
    if (values.size() != 9 && values.size() != 4)
      throw Error("--cell: expected 9 numbers (the vectors a, b, c) or 4 (a 2-D cell), found " + std::to_string(values.size()));
    const int dims = values.size() == 9 ? 3 : 2;
    cell = Cell{};
    for (int k = 0; k < dims; ++k) {
      for (int a = 0; a < dims; ++a) cell.vectors[k][a] = values[k * dims + a];
      cell.pbc[k] = true;
    }
  }
  if (!pbc.empty()) {
    if (text.empty() && cell.vectors == Cell{}.vectors) throw Error("--pbc needs --cell (or a structure file with a cell)");
    std::size_t axis = 0;
    for (std::size_t from = 0; from <= pbc.size(); ++axis) {
      const std::size_t comma = std::min(pbc.find(',', from), pbc.size());
      const std::string flag = pbc.substr(from, comma - from);
      if (axis >= 3 || (flag != "0" && flag != "1"))
        throw Error("--pbc " + pbc + ": expected a 0 or 1 per cell vector, such as 1,1,0");
      cell.pbc[axis] = flag == "1";
      from = comma + 1;
    }
    if (axis < 2) throw Error("--pbc " + pbc + ": expected a 0 or 1 per cell vector, such as 1,1,0");
  }
  return cell;
}

PairOutputs parse_outputs(const std::string& text) {
  PairOutputs outputs;
  for (char c : text) {
    if (c == ',' || c == ' ') continue;
    if (c == 'S') outputs.shifts = true;
    else if (c == 'd') outputs.distances = true;
    else if (c == 'D') outputs.vectors = true;
    else throw Error(std::string("--outputs ") + text + ": '" + c + "' is not one of S (shifts), d (distances), D (vectors)");
  }
  return outputs;
}

/// --max-memory and --gpu-max-memory (`option`): bytes, or a number with K, M, G or T (powers
/// of 1024).
std::size_t parse_memory(const std::string& option, const std::string& text) {
  if (text.empty()) return 0;
  double value = 0;
  std::size_t used = leading_number(text, value);
  const std::string unit = text.substr(used);
  const std::string units = "KMGT";
  double scale = 1;
  if (unit.size() == 1 && units.find(static_cast<char>(std::toupper(unit[0]))) != std::string::npos)
    scale = std::pow(1024.0, 1 + static_cast<double>(units.find(static_cast<char>(std::toupper(unit[0])))));
  else if (!unit.empty())
    used = 0;
  if (used == 0 || !(value > 0)) throw Error(option + " " + text + ": expected a size such as 512M or 8G");
  return static_cast<std::size_t>(value * scale);
}

SearchOptions search_options(const SearchArgs& args, const Cell& file_cell) {
  SearchOptions options;
  options.horizon = args.horizon;
  options.metric = parse_metric(args.metric);
  options.cells_per_horizon = args.cells_per_horizon;
  options.half = args.half;
  options.sort_rows = !args.unsorted;
  options.backend = parse_backend(args.backend);
  options.threads = args.threads;
  options.device = args.device;
  options.devices = parse_gpus(args.gpus);
  options.max_memory = parse_memory("--max-memory", args.max_memory);
  options.gpu_max_memory = parse_memory("--gpu-max-memory", args.gpu_max_memory);
  options.box = parse_box(args.box);
  options.cell = parse_cell(args.cell, args.pbc, file_cell);
  options.outputs = parse_outputs(args.outputs);
  options.self_interaction = args.self_interaction;
  return options;
}

void check_output(const SearchArgs& args) {
  if (args.vtk_bonds && args.vtk.empty()) throw Error("--vtk-bonds needs --vtk FILE.vtu");
  if (args.vtk_bonds && !args.queries.empty())
    throw Error("--vtk-bonds: with --queries the rows index another point set; bonds would join unrelated points");
  if (!args.vtk.empty() && (args.vtk == args.input || args.vtk == args.queries))
    throw Error("--vtk " + args.vtk + " would overwrite the input");
  for (const char* suffix : {".csv", ".offsets.npy", ".indices.npy"})
    for (const std::string& input : {args.input, args.queries})
      if (!args.out.empty() && args.out + suffix == input)
        throw Error("--out " + args.out + " would overwrite the input " + input);
}

void add_search(CLI::App& app) {
  auto args = std::make_shared<SearchArgs>();
  CLI::App* cmd = app.add_subcommand("search", "build the neighbour list of a point set");
  cmd->add_option("input", args->input,
                  "points: .npy, .csv/.xyz/.txt, Peridigm text, extended XYZ, LAMMPS data, or lattice:N")
      ->required();
  CLI::Option* horizon = cmd->add_option("--horizon", args->horizon, "pairs closer than this are neighbours");
  CLI::Option* radii = cmd->add_option("--radii", args->radii,
                                       "a radius per point (per query with --queries) instead of --horizon (.npy float, or text one per line)");
  horizon->excludes(radii);
  radii->excludes(horizon);
  cmd->add_option("--radius-rule", args->radius_rule,
                  "with --radii: gather (d < r_i), scatter (d < r_j), max or min of the two (default gather)")
      ->check(CLI::IsMember({"gather", "scatter", "max", "min"}));
  cmd->add_option("--backend", args->backend, "auto, serial, openmp or cuda")
      ->check(CLI::IsMember({"auto", "serial", "openmp", "cuda"}));
  cmd->add_option("--threads", args->threads, "openmp threads (0: all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--device", args->device, "cuda device")->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-memory", args->max_memory, "most host memory the list may take, e.g. 8G (default: what is available)");
  cmd->add_option("--gpu-max-memory", args->gpu_max_memory,
                  "cuda: most GPU memory the search may take, e.g. 2G, for a solver sharing the GPU (default: what is free)");
  cmd->add_option("--gpus", args->gpus, "cuda: all, a count N, or devices 0,1,...: one part of the points per GPU");
  cmd->add_option("--metric", args->metric, "l2, l1 or linf")->check(CLI::IsMember({"l2", "l1", "linf"}));
  cmd->add_option("--cells-per-horizon", args->cells_per_horizon, "k: cell side horizon/k")
      ->check(CLI::IsMember({1, 2, 3}));
  cmd->add_flag("--half", args->half, "each pair once, in the row of the smaller id");
  cmd->add_option("--box", args->box,
                  "periodic box Lx,Ly[,Lz] (0: open axis): points in [0, L), nearest-image distance, horizon < L/2");
  cmd->add_option("--cell", args->cell,
                  "periodic cell of any shape: \"ax ay az bx by bz cx cy cz\" (a structure file's by default)");
  cmd->add_option("--pbc", args->pbc, "which cell vectors are periodic, e.g. 1,1,0 (default: all)");
  cmd->add_option("--outputs", args->outputs, "per-entry geometry: S (shifts), d (distances), D (vectors), e.g. d,D,S");
  cmd->add_flag("--self-interaction", args->self_interaction, "with --cell or --outputs: each point is its own neighbour at shift 0");
  cmd->add_option("--queries", args->queries,
                  "query points (file or lattice:N): rows are the queries, ids index the input (the references)");
  cmd->add_flag("--unsorted", args->unsorted, "leave each family in search order (faster)");
  cmd->add_option("--out", args->out, "output prefix (PREFIX.offsets.npy + PREFIX.indices.npy, or PREFIX.csv)");
  cmd->add_option("--bond-filters", args->bond_filters,
                  "JSON array of rectangles and disks (Peridigm's): bonds whose segment crosses one are dropped");
  cmd->add_option("--blocks", args->blocks,
                  "a block id per point (.npy of integers, or text, one per line); default: a Peridigm input's block column");
  cmd->add_option("--block-pairs", args->block_pairs, "keep only bonds between these blocks, e.g. 1-1,1-2,2-2");
  cmd->add_option("--vtk", args->vtk, "also write the points for ParaView (.vtu), with each family's size (and block)");
  cmd->add_flag("--vtk-bonds", args->vtk_bonds, "with --vtk: every pair as a line cell (at most 10^7 bonds)");
  cmd->add_option("--format", args->format, "npy or csv")->check(CLI::IsMember({"npy", "csv"}));
  cmd->add_flag("--json", args->json, "print one JSON line of results and timings");
  cmd->add_flag("--quiet", args->quiet, "no progress on stderr");
#if defined(HORIZON_WITH_MPI)
  cmd->add_option("--exchange", args->exchange, "under mpirun: thesis, halo or overlap (default halo)")
      ->check(CLI::IsMember({"thesis", "halo", "overlap"}));
  cmd->add_option("--decomposition", args->decomposition, "under mpirun: rcb or brick")
      ->check(CLI::IsMember({"rcb", "brick"}));
  cmd->add_option("--writer", args->writer,
                  "under mpirun: gather (rank 0 writes), parallel (every rank writes its rows into the shared files; "
                  ".npy only) or auto")
      ->check(CLI::IsMember({"auto", "gather", "parallel"}));
#endif
  cmd->callback([args, horizon, radii] {
    if (horizon->count() == 0 && radii->count() == 0) throw Error("search: --horizon D or --radii FILE is required");
    run_search(*args);
  });
}

}  // namespace horizon::cli
