// horizon: all-pairs fixed-radius neighbour lists from the command line.
#include <unistd.h>
#if defined(HORIZON_WITH_MPI)
#include <mpi.h>
#endif

#include <cstdio>
#include <cstdlib>
#include <string>
#include <iostream>

#include "commands.hpp"
#include "horizon/error.hpp"
#include "horizon/generate.hpp"
#include "horizon/io.hpp"
#include "horizon/version.hpp"

namespace horizon::cli {

PointSet load_input(const std::string& input) {
  const std::string lattice_prefix = "lattice:";
  if (input.rfind(lattice_prefix, 0) == 0) {
    int n = 0;
    try {
      n = std::stoi(input.substr(lattice_prefix.size()));
    } catch (const std::exception&) {
    }
    if (n < 1) throw Error("'" + input + "': expected lattice:N with N >= 1");
    return lattice(n);
  }
  return read_points(input);
}

Structure load_structure(const std::string& input) {
  if (input.rfind("lattice:", 0) != 0 && is_structure_file(input)) return read_structure(input);
  return Structure{load_input(input), Cell{}};
}

Progress::Progress(bool quiet) : on_(!quiet && ::isatty(STDERR_FILENO)) {}

void Progress::say(const std::string& what) const {
  if (on_) std::fprintf(stderr, "horizon: %s\n", what.c_str());
}

}  // namespace horizon::cli

namespace {

#if defined(HORIZON_WITH_MPI)
// MPI starts only for runs that ask for it: under mpirun, or with --exchange (a one-rank run).
struct MpiSession {
  MpiSession(int& argc, char**& argv) {
    bool wanted = std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE");
    for (int i = 1; i < argc; ++i) wanted = wanted || std::string(argv[i]).rfind("--exchange", 0) == 0;
    if (wanted) MPI_Init(&argc, &argv);
    active = wanted;
  }
  ~MpiSession() {
    if (active) MPI_Finalize();
  }
  // A failure on one rank must not leave the others waiting in a collective.
  void abort(int status) const {
    int size = 1;
    if (active) MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size > 1) MPI_Abort(MPI_COMM_WORLD, status);
  }
  int rank() const {
    int rank = 0;
    if (active) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    return rank;
  }
  bool active = false;
};
#else
struct MpiSession {
  MpiSession(int&, char**&) {}
  void abort(int) const {}
  int rank() const { return 0; }
};
#endif

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  CLI::App app{"horizon: all-pairs fixed-radius neighbour lists (cell lists, CPU and GPU)"};
  app.set_version_flag("--version", std::string("horizon ") + horizon::version());
  app.require_subcommand(1);
  horizon::cli::add_generate(app);
  horizon::cli::add_search(app);
  horizon::cli::add_verify(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const horizon::cli::VerifyFailed&) {
    return 1;
  } catch (const horizon::CollectiveError& e) {  // every rank has it: one message, no abort
    if (mpi.rank() == 0) std::cerr << "horizon: error: " << e.what() << "\n";
    return 2;
  } catch (const horizon::Error& e) {
    std::cerr << "horizon: error: " << e.what() << "\n";
    mpi.abort(2);
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "horizon: error: out of memory (the neighbour list does not fit)\n";
    mpi.abort(2);
    return 2;
  }
  return 0;
}
