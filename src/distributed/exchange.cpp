#include "exchange.hpp"

#include <limits>
#include <numeric>

#include "horizon/error.hpp"

namespace horizon::detail {

namespace {

// MPI counts are int: displacements and counts in units of Packed must fit.
int as_count(std::size_t n) {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("a rank would send more than 2^31 points in one exchange; use more ranks");
  return static_cast<int>(n);
}

// The first `width` doubles of a Packed (4 or 5), its stride a whole Packed.
MPI_Datatype packed_type(int width) {
  static const auto make = [](int doubles) {
    MPI_Datatype part, t;
    MPI_Type_contiguous(doubles, MPI_DOUBLE, &part);
    MPI_Type_create_resized(part, 0, sizeof(Packed), &t);
    MPI_Type_free(&part);
    MPI_Type_commit(&t);
    return t;
  };
  static MPI_Datatype types[2] = {make(4), make(5)};
  return types[width == 5 ? 1 : 0];
}

struct Layout {
  std::vector<int> send_counts, send_displs, recv_counts, recv_displs;
  std::vector<Packed> send;
};

// Counts what goes to other ranks (`self` is this rank's index in outgoing, or -1).
Layout pack(const std::vector<std::vector<Packed>>& outgoing, int self, int width, Traffic& traffic) {
  Layout l;
  for (std::size_t r = 0; r < outgoing.size(); ++r) {
    const auto& out = outgoing[r];
    l.send_displs.push_back(as_count(l.send.size()));
    l.send_counts.push_back(as_count(out.size()));
    l.send.insert(l.send.end(), out.begin(), out.end());
    if (!out.empty() && static_cast<int>(r) != self) {
      traffic.messages += 1;
      traffic.bytes += static_cast<std::int64_t>(out.size() * sizeof(double)) * width;
    }
  }
  return l;
}

void displace(Layout& l) {
  l.recv_displs.resize(l.recv_counts.size());
  std::size_t at = 0;
  for (std::size_t r = 0; r < l.recv_counts.size(); ++r) {
    l.recv_displs[r] = as_count(at);
    at += static_cast<std::size_t>(l.recv_counts[r]);
  }
}

// Counts first, then the points; MPI_Alltoall[v] and MPI_Neighbor_alltoall[v] share signatures.
using CountExchange = decltype(&MPI_Alltoall);
using DataExchange = decltype(&MPI_Alltoallv);

std::vector<Packed> exchange(MPI_Comm comm, const std::vector<std::vector<Packed>>& outgoing, int self, int width,
                             Traffic& traffic, CountExchange counts, DataExchange data) {
  Layout l = pack(outgoing, self, width, traffic);
  l.recv_counts.resize(outgoing.size());
  counts(l.send_counts.data(), 1, MPI_INT, l.recv_counts.data(), 1, MPI_INT, comm);
  displace(l);
  std::vector<Packed> received(static_cast<std::size_t>(std::accumulate(l.recv_counts.begin(), l.recv_counts.end(), 0LL)));
  data(l.send.data(), l.send_counts.data(), l.send_displs.data(), packed_type(width), received.data(),
       l.recv_counts.data(), l.recv_displs.data(), packed_type(width), comm);
  return received;
}

}  // namespace

std::vector<Packed> exchange_all(MPI_Comm comm, const std::vector<std::vector<Packed>>& outgoing, int width,
                                 Traffic& traffic) {
  int self = 0;
  MPI_Comm_rank(comm, &self);
  return exchange(comm, outgoing, self, width, traffic, &MPI_Alltoall, &MPI_Alltoallv);
}

std::vector<Packed> exchange_with(MPI_Comm graph, const std::vector<std::vector<Packed>>& outgoing, int width,
                                  Traffic& traffic) {
  return exchange(graph, outgoing, -1, width, traffic, &MPI_Neighbor_alltoall, &MPI_Neighbor_alltoallv);
}

}  // namespace horizon::detail
