#pragma once
/// \file distributed.hpp
/// Neighbour lists across MPI ranks. Each rank owns part of the points, receives the ghost
/// points within the horizon of its sub-domain, searches locally with any node-local backend,
/// and returns the rows of the points it owns with global ids. For any rank count the union of
/// the rows equals the serial list exactly.
#include <mpi.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "horizon/decomposition.hpp"
#include "horizon/radii.hpp"
#include "horizon/search.hpp"

namespace horizon {

/// How ghost points reach the ranks that need them.
enum class Exchange {
  thesis,   ///< thesis §4.5: partition by input order; every rank sends to every other rank the
            ///< points in cells adjacent to that rank's occupied cells
  halo,     ///< spatial decomposition, migration of points to their owners, then a halo
            ///< exchange with spatial neighbours only (message sizes first)
  overlap,  ///< every rank reads all points and keeps its sub-domain plus a horizon-wide halo:
            ///< no point data moves between ranks (thesis ch. 5 / future work)
};
Exchange parse_exchange(const std::string& name);
const char* exchange_name(Exchange exchange);

struct DistributedOptions {
  SearchOptions search;  ///< the node-local search every rank runs
  Exchange exchange = Exchange::halo;
  Decomposition::Kind decomposition = Decomposition::Kind::rcb;  ///< halo and overlap
};

/// Per-phase seconds (maximum over ranks) and traffic (sums over ranks, and the busiest rank).
struct DistributedStats {
  double preprocess = 0, decompose = 0, communicate = 0, search = 0, gather = 0;
  std::int64_t bytes_sent = 0, messages_sent = 0, max_bytes_sent = 0, max_messages_sent = 0;
  std::int64_t ghosts = 0;                    ///< ghost points summed over ranks
  std::int64_t min_owned = 0, max_owned = 0;  ///< owned points per rank
  int ranks = 1;
};

/// The families of the points one rank owns: ids[r] is the global id of row r.
struct OwnedRows {
  std::vector<std::int64_t> ids;
  NeighborList rows;  ///< neighbours as global ids, sorted; half lists keep j > i globally
};

/// Collective over `comm`. With thesis or halo, `points` are the points this rank holds and
/// `ids` their global ids (any split; a rank may hold none). With overlap, every rank passes
/// all points and ids is ignored.
///
/// A periodic cell of any shape (SearchOptions::cell), shifts, distances or vectors
/// (SearchOptions::outputs) and self_interaction are searched as on one node (cell.hpp): the
/// rows carry their geometry and equal search()'s. Each rank then holds the points of one
/// block of ids (they move there first, whatever the split), makes their periodic images and
/// finds every point's candidates among all images with the query search below (overlap uses
/// the halo exchange for it); the ids must be 0 to global_count - 1, each held once.
OwnedRows search_distributed(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                             std::size_t global_count, const DistributedOptions& options,
                             DistributedStats* stats = nullptr);

/// As above, each held point with its own radius (`radii`, one per point of `points`) combined
/// by `rule` (radii.hpp); options.search.horizon is ignored. The ghosts reach the largest
/// radius of all ranks and carry their radii; the rows equal search_with_radii's.
OwnedRows search_distributed(MPI_Comm comm, PointView points, const std::vector<std::int64_t>& ids,
                             std::span<const double> radii, RadiusRule rule, std::size_t global_count,
                             const DistributedOptions& options, DistributedStats* stats = nullptr);

/// Collective: the families of query points among reference points (full lists, nothing
/// excluded as self), as search(queries, references, ...) on one node: row q holds every
/// reference within the horizon or, with `radii` (one per held query), within its query's own
/// radius. Queries and references are held as `points` and `ids` above (with overlap every rank
/// passes all of both). OwnedRows.ids are query ids; entries are reference ids.
OwnedRows search_distributed_queries(MPI_Comm comm, PointView queries, const std::vector<std::int64_t>& query_ids,
                                     std::size_t global_queries, PointView references,
                                     const std::vector<std::int64_t>& reference_ids, std::size_t global_references,
                                     const DistributedOptions& options, std::span<const double> radii = {},
                                     DistributedStats* stats = nullptr);

/// Collective: the whole list in global id order on `root` (an empty list elsewhere), with the
/// shifts, distances and vectors a cell search computed, sent point to point by rank in chunks
/// (no 2^31 limit on a rank's entries).
NeighborList gather_rows(MPI_Comm comm, const OwnedRows& owned, std::size_t global_count, bool half,
                         int root = 0);

/// Collective: whether the list gather_rows assembles on `root` (and the rows it receives on
/// the way) fits in root's memory: SearchOptions::max_memory, else what root's system reports
/// available. The same answer on every rank.
bool gather_fits(MPI_Comm comm, std::int64_t entries, const SearchOptions& options, int root = 0);

/// Collective: writes PREFIX.indices.npy and PREFIX.offsets.npy (and the geometry files of a
/// cell search's outputs), byte for byte the files of
/// write_neighbor_list(prefix, gather_rows(...)), each rank writing its own rows at their
/// offsets with positioned writes (no rank holds the whole list; every rank must see the
/// directory). Under temporary names, renamed once every rank has written; throws
/// CollectiveError on every rank when any failed. Returns the paths.
std::string write_rows_parallel(MPI_Comm comm, const OwnedRows& owned, std::size_t global_count,
                                const std::string& prefix);

}  // namespace horizon
