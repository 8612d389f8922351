// Every rank writes the rows it owns straight into PREFIX.indices.npy and PREFIX.offsets.npy
// through MPI-IO, at the offsets a distributed scan of the row lengths gives: no rank holds the
// whole list. The files are byte-identical to write_neighbor_list of the gathered list and as
// atomic: written under temporary names, renamed by rank 0 once every rank has written its part.
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>

#include "../io/npy.hpp"
#include "horizon/distributed.hpp"
#include "horizon/error.hpp"

namespace horizon {

namespace {

// Entries one rank writes per collective call (1 GiB of int32): keeps every count an int.
constexpr std::int64_t round_entries = std::int64_t{1} << 28;

/// Throws CollectiveError on every rank when any rank failed, with the first failing rank's message.
void agree(MPI_Comm comm, const std::string& failure) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int mine = failure.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  std::string message = failure;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  throw CollectiveError(message);
}

std::string mpi_error(const std::string& path, const char* what, int code) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  return path + ": " + what + " failed (" + std::string(text, static_cast<std::size_t>(length)) + ")";
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

/// A run of entries that is contiguous in the indices file.
struct Segment {
  MPI_Offset byte;  ///< position in the file
  std::int64_t entries;
};

class SharedFile {
public:
  SharedFile(MPI_Comm comm, const std::string& path, const std::string& temporary, MPI_Offset bytes)
      : comm_(comm), path_(path) {
    int code = MPI_File_open(comm, temporary.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file_);
    agree(comm, code == MPI_SUCCESS ? "" : mpi_error(path, "opening", code));
    code = MPI_File_set_size(file_, bytes);
    check(code, "sizing");
  }
  ~SharedFile() {
    if (file_ != MPI_FILE_NULL) MPI_File_close(&file_);
  }
  SharedFile(const SharedFile&) = delete;
  SharedFile& operator=(const SharedFile&) = delete;
  MPI_File handle() const { return file_; }
  /// Collective: throws on every rank when `code` failed on any.
  void check(int code, const char* what) const { agree(comm_, code == MPI_SUCCESS ? "" : mpi_error(path_, what, code)); }
  void close() {
    const int code = MPI_File_close(&file_);
    check(code, "closing");
  }

private:
  MPI_Comm comm_;
  std::string path_;
  MPI_File file_ = MPI_FILE_NULL;
};

void write_header(const SharedFile& file, const std::string& header, int rank) {
  int code = MPI_SUCCESS;
  if (rank == 0)
    code = MPI_File_write_at(file.handle(), 0, header.data(), static_cast<int>(header.size()), MPI_BYTE,
                             MPI_STATUS_IGNORE);
  file.check(code, "writing the header");
}

void write_indices(const SharedFile& file, const OwnedRows& owned, const std::vector<std::size_t>& by_id,
                   const std::vector<std::int64_t>& row_offset, MPI_Offset data_start, MPI_Comm comm) {
  // This rank's rows in id order, cut into rounds of at most round_entries entries; a round is
  // a list of file segments and the entries packed in the same order.
  struct Piece {
    std::size_t row;
    std::int64_t from, entries;  // within the row
  };
  std::vector<std::vector<Piece>> rounds(1);
  std::int64_t in_round = 0;
  for (std::size_t row : by_id) {
    const auto length = static_cast<std::int64_t>(owned.rows.row_size(row));
    for (std::int64_t from = 0; from < length;) {
      if (in_round == round_entries) {
        rounds.emplace_back();
        in_round = 0;
      }
      const std::int64_t take = std::min(length - from, round_entries - in_round);
      rounds.back().push_back({row, from, take});
      from += take;
      in_round += take;
    }
  }
  int mine = static_cast<int>(rounds.size()), count = 0;
  MPI_Allreduce(&mine, &count, 1, MPI_INT, MPI_MAX, comm);
  std::vector<point_id> packed;
  for (int r = 0; r < count; ++r) {
    std::vector<Segment> segments;
    packed.clear();
    if (r < mine)
      for (const Piece& piece : rounds[static_cast<std::size_t>(r)]) {
        const MPI_Offset byte = data_start + 4 * (row_offset[piece.row] + piece.from);
        if (!segments.empty() && segments.back().byte + 4 * segments.back().entries == byte)
          segments.back().entries += piece.entries;
        else
          segments.push_back({byte, piece.entries});
        const point_id* row = owned.rows.row(piece.row).data() + piece.from;
        packed.insert(packed.end(), row, row + piece.entries);
      }
    MPI_Datatype view = MPI_INT32_T;
    if (!segments.empty()) {
      std::vector<int> lengths(segments.size());
      std::vector<MPI_Aint> bytes(segments.size());
      for (std::size_t s = 0; s < segments.size(); ++s) {
        lengths[s] = static_cast<int>(segments[s].entries);
        bytes[s] = static_cast<MPI_Aint>(segments[s].byte);
      }
      MPI_Type_create_hindexed(static_cast<int>(segments.size()), lengths.data(), bytes.data(), MPI_INT32_T, &view);
      MPI_Type_commit(&view);
    }
    int code = MPI_File_set_view(file.handle(), 0, MPI_INT32_T, view, "native", MPI_INFO_NULL);
    if (code == MPI_SUCCESS)
      code = MPI_File_write_all(file.handle(), packed.data(), static_cast<int>(packed.size()), MPI_INT32_T,
                                MPI_STATUS_IGNORE);
    if (view != MPI_INT32_T) MPI_Type_free(&view);
    file.check(code, "writing the rows");
  }
}

}  // namespace

std::string write_rows_parallel(MPI_Comm comm, const OwnedRows& owned, std::size_t global_count,
                                const std::string& prefix) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string offsets_path = prefix + ".offsets.npy", indices_path = prefix + ".indices.npy";
  std::string failure;
  if (rank == 0) {
    const auto directory = std::filesystem::path(prefix).parent_path();
    if (!directory.empty() && !std::filesystem::is_directory(directory))
      failure = offsets_path + ": output directory '" + directory.string() + "' does not exist";
  }
  agree(comm, failure);

  std::vector<std::size_t> by_id(owned.ids.size());
  std::iota(by_id.begin(), by_id.end(), std::size_t{0});
  std::sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return owned.ids[a] < owned.ids[b]; });
  const Offsets offsets = scan_offsets(comm, owned, by_id, global_count);
  std::int64_t total = 0;
  const std::int64_t mine = owned.rows.total();
  MPI_Allreduce(&mine, &total, 1, MPI_INT64_T, MPI_SUM, comm);

  long tag = rank == 0 ? static_cast<long>(::getpid()) : 0;
  MPI_Bcast(&tag, 1, MPI_LONG, 0, comm);
  const std::string suffix = ".tmp." + std::to_string(tag);
  const std::string indices_header = detail::npy_header("i4", {static_cast<std::size_t>(total)});
  const std::string offsets_header = detail::npy_header("i8", {global_count + 1});
  try {
    SharedFile indices(comm, indices_path, indices_path + suffix,
                       static_cast<MPI_Offset>(indices_header.size()) + 4 * total);
    write_header(indices, indices_header, rank);
    write_indices(indices, owned, by_id, offsets.of_row, static_cast<MPI_Offset>(indices_header.size()), comm);
    indices.close();

    SharedFile list(comm, offsets_path, offsets_path + suffix,
                    static_cast<MPI_Offset>(offsets_header.size() + 8 * (global_count + 1)));
    write_header(list, offsets_header, rank);
    const int code = MPI_File_write_at_all(
        list.handle(), static_cast<MPI_Offset>(offsets_header.size() + 8 * offsets.block_first),
        offsets.block.data(), static_cast<int>(offsets.block.size()), MPI_INT64_T, MPI_STATUS_IGNORE);
    list.check(code, "writing the offsets");
    list.close();

    // Offsets go last, as in a serial write: once they are in place the indices are complete.
    if (rank == 0)
      for (const std::string& path : {indices_path, offsets_path})
        if (failure.empty() && std::rename((path + suffix).c_str(), path.c_str()) != 0)
          failure = path + ": cannot finish writing (" + std::strerror(errno) + ")";
    agree(comm, failure);
  } catch (const Error&) {
    if (rank == 0)
      for (const std::string& path : {indices_path, offsets_path}) std::remove((path + suffix).c_str());
    throw;
  }
  return offsets_path + "," + indices_path;
}

}  // namespace horizon
