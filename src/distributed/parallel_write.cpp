// Every rank writes the rows it owns straight into PREFIX.indices.npy and PREFIX.offsets.npy
// (and a cell search's PREFIX.shifts.npy, .distances.npy, .vectors.npy) with positioned writes
// (the files must be on a filesystem every rank sees), at the offsets a distributed scan of the
// row lengths gives: no rank holds the whole list. The files are byte-identical to
// write_neighbor_list of the gathered list and as atomic: written under temporary names,
// renamed by rank 0 once every rank has written its part. (MPI-IO collective
// writes, OMPIO and ROMIO, were tried first: 2-3x slower than these at 4 ranks on a local disk.)
#include <fcntl.h>
#include <limits.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>

#include "../io/npy.hpp"
#include "agree.hpp"
#include "horizon/distributed.hpp"
#include "horizon/error.hpp"

namespace horizon {

namespace {

using detail::agree;

/// This rank's rows in ascending id order. The ids arrive as a few ascending runs (one per rank
/// its points came from): the runs are merged, not sorted.
std::vector<std::size_t> rows_by_id(const std::vector<std::int64_t>& ids) {
  std::vector<std::uint64_t> keys(ids.size());  // id in the high half, row in the low half
  std::vector<std::size_t> runs{0};
  for (std::size_t row = 0; row < ids.size(); ++row) {
    keys[row] = static_cast<std::uint64_t>(ids[row]) << 32 | row;
    if (row > 0 && ids[row] < ids[row - 1]) runs.push_back(row);
  }
  runs.push_back(ids.size());
  for (std::size_t width = 1; width + 1 < runs.size(); width *= 2)  // bottom-up pairwise merges
    for (std::size_t r = 0; r + width + 1 < runs.size(); r += 2 * width)
      std::inplace_merge(keys.begin() + static_cast<std::ptrdiff_t>(runs[r]),
                         keys.begin() + static_cast<std::ptrdiff_t>(runs[r + width]),
                         keys.begin() + static_cast<std::ptrdiff_t>(runs[std::min(r + 2 * width, runs.size() - 1)]));
  std::vector<std::size_t> rows(ids.size());
  for (std::size_t k = 0; k < rows.size(); ++k) rows[k] = static_cast<std::size_t>(keys[k] & 0xffffffffu);
  return rows;
}

/// The global offset of each of this rank's rows. Row lengths go to the rank that owns their
/// id's block of [0, n) (rank r: [n r / P, n (r+1) / P)); each block is scanned, the blocks are
/// scanned across ranks, and the offsets come back. `by_id` lists this rank's rows in id order.
/// Also returns this rank's block of the offsets array (the last rank's ends with the total).
struct Offsets {
  std::vector<std::int64_t> of_row, block;
  std::size_t block_first = 0;
};

Offsets scan_offsets(MPI_Comm comm, const OwnedRows& owned, const std::vector<std::size_t>& by_id, std::size_t n) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  auto first = [&](int r) { return n * static_cast<std::size_t>(r) / static_cast<std::size_t>(size); };
  std::vector<int> send_counts(static_cast<std::size_t>(size), 0), receive_counts(send_counts.size());
  std::vector<std::int64_t> pairs;
  pairs.reserve(2 * by_id.size());
  int to = 0;
  for (std::size_t row : by_id) {
    const auto id = static_cast<std::size_t>(owned.ids[row]);
    while (id >= first(to + 1)) ++to;
    ++send_counts[static_cast<std::size_t>(to)];
    pairs.push_back(static_cast<std::int64_t>(id));
    pairs.push_back(static_cast<std::int64_t>(owned.rows.row_size(row)));
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
  std::vector<int> send_at(send_counts.size()), receive_at(send_counts.size());
  std::exclusive_scan(send_counts.begin(), send_counts.end(), send_at.begin(), 0);
  std::exclusive_scan(receive_counts.begin(), receive_counts.end(), receive_at.begin(), 0);
  std::vector<std::int64_t> received(2 * static_cast<std::size_t>(receive_at.back() + receive_counts.back()));
  MPI_Datatype pair;
  MPI_Type_contiguous(2, MPI_INT64_T, &pair);
  MPI_Type_commit(&pair);
  MPI_Alltoallv(pairs.data(), send_counts.data(), send_at.data(), pair, received.data(), receive_counts.data(),
                receive_at.data(), pair, comm);
  MPI_Type_free(&pair);

  Offsets result;
  result.block_first = first(rank);
  const std::size_t block_size = first(rank + 1) - result.block_first;
  std::vector<std::int64_t> lengths(block_size, 0);
  for (std::size_t p = 0; p < received.size(); p += 2)
    lengths[static_cast<std::size_t>(received[p]) - result.block_first] = received[p + 1];
  const std::int64_t block_total = std::accumulate(lengths.begin(), lengths.end(), std::int64_t{0});
  std::int64_t base = 0;
  MPI_Exscan(&block_total, &base, 1, MPI_INT64_T, MPI_SUM, comm);
  if (rank == 0) base = 0;  // MPI_Exscan leaves rank 0's result undefined
  result.block.resize(block_size + (rank == size - 1 ? 1 : 0));
  std::exclusive_scan(lengths.begin(), lengths.end(), result.block.begin(), base);
  if (rank == size - 1) result.block.back() = base + block_total;

  // Each row's offset goes back to the rank that sent its length, in the order it was sent.
  std::vector<std::int64_t> answers(received.size() / 2), back(by_id.size());
  for (std::size_t p = 0; p < answers.size(); ++p)
    answers[p] = result.block[static_cast<std::size_t>(received[2 * p]) - result.block_first];
  MPI_Alltoallv(answers.data(), receive_counts.data(), receive_at.data(), MPI_INT64_T, back.data(),
                send_counts.data(), send_at.data(), MPI_INT64_T, comm);
  result.of_row.resize(by_id.size());
  for (std::size_t k = 0; k < by_id.size(); ++k) result.of_row[by_id[k]] = back[k];
  return result;
}

/// A file every rank writes parts of with positioned writes (pwrite), created and sized by rank 0
/// before the others open it.
class SharedFile {
public:
  SharedFile(MPI_Comm comm, const std::string& path, const std::string& temporary, std::int64_t bytes)
      : comm_(comm), path_(path) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::string failure;
    if (rank == 0) {
      fd_ = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd_ < 0 || ::ftruncate(fd_, static_cast<off_t>(bytes)) != 0) failure = reason("cannot write");
    }
    agree(comm, failure);
    if (rank != 0) {
      fd_ = ::open(temporary.c_str(), O_WRONLY);
      if (fd_ < 0) failure = reason("cannot open the shared file");
    }
    agree(comm, failure);
  }
  ~SharedFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  SharedFile(const SharedFile&) = delete;
  SharedFile& operator=(const SharedFile&) = delete;

  /// Writes the pieces one after another from file position `at`; returns a failure or "".
  std::string write(std::int64_t at, std::vector<iovec>& pieces) const {
    for (std::size_t first = 0; first < pieces.size();) {
      const int count = static_cast<int>(std::min<std::size_t>(IOV_MAX, pieces.size() - first));
      const ssize_t wrote = ::pwritev(fd_, &pieces[first], count, static_cast<off_t>(at));
      if (wrote <= 0) return reason("write failed");
      at += wrote;
      for (auto left = static_cast<std::size_t>(wrote); left > 0;) {  // skip what was written
        const std::size_t take = std::min(left, pieces[first].iov_len);
        pieces[first].iov_base = static_cast<char*>(pieces[first].iov_base) + take;
        pieces[first].iov_len -= take;
        left -= take;
        if (pieces[first].iov_len == 0) ++first;
      }
      while (first < pieces.size() && pieces[first].iov_len == 0) ++first;
    }
    return "";
  }
  /// Collective: closes the file on every rank; throws on every rank when any failed.
  void close(const std::string& failure) {
    const bool closed = ::close(fd_) == 0;
    fd_ = -1;
    agree(comm_, !failure.empty() ? failure : closed ? "" : reason("cannot finish writing"));
  }

private:
  std::string reason(const char* what) const { return path_ + ": " + what + " (" + std::strerror(errno) + ")"; }
  MPI_Comm comm_;
  std::string path_;
  int fd_ = -1;
};

/// One of the list's per-entry arrays (the ids, or a geometry array): its file, its npy dtype
/// and shape per entry, and this rank's entries (`bytes` each, in the rows' order).
struct EntryArray {
  std::string path;
  const char* dtype;
  std::vector<std::size_t> shape;  ///< the file's shape, entries first
  const char* data;
  std::size_t bytes;
};

/// This rank's rows in id order as runs contiguous in the file (each a list of pieces of
/// memory, merged where rows are adjacent in memory too), each run written with pwritev.
std::string write_entries(const SharedFile& file, const OwnedRows& owned, const EntryArray& array,
                          const std::vector<std::size_t>& by_id, const std::vector<std::int64_t>& row_offset,
                          std::int64_t data_start) {
  const auto item = static_cast<std::int64_t>(array.bytes);
  std::int64_t run_at = -1, run_end = -1;
  std::vector<iovec> run;
  for (std::size_t row : by_id) {
    const std::size_t entries = owned.rows.row_size(row);
    if (entries == 0) continue;
    const std::int64_t at = data_start + item * row_offset[row];
    if (at != run_end) {
      if (!run.empty()) {
        if (std::string failure = file.write(run_at, run); !failure.empty()) return failure;
      }
      run.clear();
      run_at = at;
    }
    auto* base = const_cast<char*>(array.data) + item * owned.rows.offsets()[row];
    const std::size_t bytes = array.bytes * entries;
    if (!run.empty() && static_cast<char*>(run.back().iov_base) + run.back().iov_len == base)
      run.back().iov_len += bytes;
    else
      run.push_back({base, bytes});
    run_end = at + static_cast<std::int64_t>(bytes);
  }
  return run.empty() ? "" : file.write(run_at, run);
}

}  // namespace

std::string write_rows_parallel(MPI_Comm comm, const OwnedRows& owned, std::size_t global_count,
                                const std::string& prefix) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string offsets_path = prefix + ".offsets.npy";
  std::string failure;
  if (rank == 0) {
    const auto directory = std::filesystem::path(prefix).parent_path();
    if (!directory.empty() && !std::filesystem::is_directory(directory))
      failure = offsets_path + ": output directory '" + directory.string() + "' does not exist";
  }
  agree(comm, failure);

  const std::vector<std::size_t> by_id = rows_by_id(owned.ids);
  const Offsets offsets = scan_offsets(comm, owned, by_id, global_count);
  std::int64_t total = 0;
  const std::int64_t mine = owned.rows.total();
  MPI_Allreduce(&mine, &total, 1, MPI_INT64_T, MPI_SUM, comm);

  // The files of write_neighbor_list: the geometry a cell search carries, the ids, the offsets.
  const NeighborList& rows = owned.rows;
  const auto entries = static_cast<std::size_t>(total), dims = static_cast<std::size_t>(rows.geometry_dims());
  std::vector<EntryArray> arrays;
  const auto bytes = [](const auto& buffer) { return reinterpret_cast<const char*>(buffer.data()); };
  const PairOutputs& outputs = rows.outputs();
  if (outputs.shifts) arrays.push_back({prefix + ".shifts.npy", "i4", {entries, dims}, bytes(rows.shifts()), 4 * dims});
  if (outputs.distances) arrays.push_back({prefix + ".distances.npy", "f8", {entries}, bytes(rows.distances()), 8});
  if (outputs.vectors)
    arrays.push_back({prefix + ".vectors.npy", "f8", {entries, dims}, bytes(rows.vectors()), 8 * dims});
  arrays.push_back({prefix + ".indices.npy", "i4", {entries}, bytes(rows.indices()), 4});
  std::vector<std::string> paths;
  for (const EntryArray& array : arrays) paths.push_back(array.path);
  paths.push_back(offsets_path);

  long tag = rank == 0 ? static_cast<long>(::getpid()) : 0;
  MPI_Bcast(&tag, 1, MPI_LONG, 0, comm);
  const std::string suffix = ".tmp." + std::to_string(tag);
  auto header_piece = [](const std::string& header) {
    return std::vector<iovec>{{const_cast<char*>(header.data()), header.size()}};
  };
  try {
    for (const EntryArray& array : arrays) {
      const std::string header = detail::npy_header(array.dtype, array.shape);
      SharedFile file(comm, array.path, array.path + suffix,
                      static_cast<std::int64_t>(header.size() + array.bytes * entries));
      std::vector<iovec> piece = header_piece(header);
      failure = rank == 0 ? file.write(0, piece) : "";
      if (failure.empty())
        failure = write_entries(file, owned, array, by_id, offsets.of_row, static_cast<std::int64_t>(header.size()));
      file.close(failure);
    }

    const std::string offsets_header = detail::npy_header("i8", {global_count + 1});
    SharedFile list(comm, offsets_path, offsets_path + suffix,
                    static_cast<std::int64_t>(offsets_header.size() + 8 * (global_count + 1)));
    std::vector<iovec> header = header_piece(offsets_header);
    failure = rank == 0 ? list.write(0, header) : "";
    std::vector<iovec> block{{const_cast<std::int64_t*>(offsets.block.data()), 8 * offsets.block.size()}};
    if (failure.empty() && !offsets.block.empty())
      failure = list.write(static_cast<std::int64_t>(offsets_header.size() + 8 * offsets.block_first), block);
    list.close(failure);

    // Offsets go last, as in a serial write: once they are in place the entries are complete.
    if (rank == 0)
      for (const std::string& path : paths)
        if (failure.empty() && std::rename((path + suffix).c_str(), path.c_str()) != 0)
          failure = path + ": cannot finish writing (" + std::strerror(errno) + ")";
    agree(comm, failure);
  } catch (const Error&) {
    if (rank == 0)
      for (const std::string& path : paths) std::remove((path + suffix).c_str());
    throw;
  }
  std::string written = offsets_path + "," + arrays.back().path;  // as write_neighbor_list names them
  for (std::size_t k = 0; k + 1 < arrays.size(); ++k) written += "," + arrays[k].path;
  return written;
}

}  // namespace horizon
