#include "horizon/decomposition.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace horizon {

double halo_reach(const Bounds& box, int dims, double horizon) {
  double magnitude = 0;
  for (int a = 0; a < dims; ++a) magnitude = std::max({magnitude, std::abs(box.lo[a]), std::abs(box.hi[a])});
  return horizon * (1 + std::ldexp(1.0, -40)) + std::ldexp(magnitude, -48);
}

bool Box::contains(const double* x, int dims) const {
  for (int a = 0; a < dims; ++a)
    if (x[a] < lo[a] || x[a] >= hi[a]) return false;
  return true;
}

bool Box::near(const double* x, int dims, double reach) const {
  for (int a = 0; a < dims; ++a)
    if (x[a] <= lo[a] - reach || x[a] >= hi[a] + reach) return false;
  return true;
}

namespace {

// The global box, its upper faces pushed out to the next double so that [lo, hi) holds every
// point; 2-D boxes are degenerate in z.
Box open_box(const Bounds& b, int dims) {
  Box box;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = a < dims ? b.lo[a] : -std::numeric_limits<double>::infinity();
    box.hi[a] = a < dims ? std::nextafter(b.hi[a], std::numeric_limits<double>::infinity())
                         : std::numeric_limits<double>::infinity();
  }
  return box;
}

}  // namespace

Decomposition Decomposition::brick(const Bounds& bounds, int dims, int ranks) {
  Decomposition d;
  d.dims_ = dims;
  const Box whole = open_box(bounds, dims);
  // Choose px * py * pz = ranks minimising the total cut area of the box.
  std::array<double, 3> extent{};
  for (int a = 0; a < 3; ++a) extent[a] = a < dims ? std::max(whole.hi[a] - whole.lo[a], 1e-300) : 1.0;
  std::array<int, 3> best{ranks, 1, 1};
  double best_area = std::numeric_limits<double>::infinity();
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px) continue;
    for (int py = 1; py <= ranks / px; ++py) {
      if ((ranks / px) % py) continue;
      const int pz = ranks / px / py;
      if (dims == 2 && pz != 1) continue;
      const double area = (px - 1) * extent[1] * extent[2] + (py - 1) * extent[0] * extent[2] +
                          (pz - 1) * extent[0] * extent[1];
      if (area < best_area) {
        best_area = area;
        best = {px, py, pz};
      }
    }
  }
  // A brick is a tree too: halve the range of slabs along x, then y, then z, cutting at slab
  // boundaries, so owner() is a walk of log2(ranks) cuts.
  auto boundary = [&](int axis, int slab) {
    return slab == best[axis] ? whole.hi[axis]
                              : whole.lo[axis] + (whole.hi[axis] - whole.lo[axis]) * slab / best[axis];
  };
  d.boxes_.resize(static_cast<std::size_t>(ranks));
  std::array<int, 3> slab{0, 0, 0};
  auto split = [&](auto&& self, int axis, int first, int last) -> int {
    if (last - first == 1) {
      slab[axis] = first;
      if (axis < 2) return self(self, axis + 1, 0, best[axis + 1]);
      Box box;
      for (int a = 0; a < 3; ++a) {
        box.lo[a] = boundary(a, slab[a]);
        box.hi[a] = boundary(a, slab[a] + 1);
      }
      const int rank = slab[0] + best[0] * (slab[1] + best[1] * slab[2]);
      d.boxes_[static_cast<std::size_t>(rank)] = box;
      return -1 - rank;
    }
    const int middle = (first + last) / 2;
    const int node = static_cast<int>(d.tree_.size());
    d.tree_.push_back({axis, boundary(axis, middle), 0, 0});
    const int below = self(self, axis, first, middle);
    const int above = self(self, axis, middle, last);
    d.tree_[static_cast<std::size_t>(node)].below = below;
    d.tree_[static_cast<std::size_t>(node)].above = above;
    return node;
  };
  split(split, 0, 0, best[0]);
  return d;
}

Decomposition Decomposition::rcb(const Bounds& bounds, PointView sample, int ranks) {
  Decomposition d;
  d.dims_ = sample.dims();
  d.boxes_.resize(static_cast<std::size_t>(ranks));
  // The sample's points themselves, reordered in place: the selections compare contiguous values
  // (through an id per point they missed the cache at every comparison, 10 ms for 2^17 points).
  std::vector<std::array<double, 3>> xs(sample.size(), {0, 0, 0});
  for (std::size_t i = 0; i < sample.size(); ++i)
    for (int a = 0; a < d.dims_; ++a) xs[i][a] = sample(i, a);
  auto split = [&](auto&& self, const Box& box, std::size_t first, std::size_t last, int first_rank,
                   int rank_count) -> int {
    if (rank_count == 1) {
      d.boxes_[static_cast<std::size_t>(first_rank)] = box;
      return -1 - first_rank;
    }
    int axis = 0;
    for (int a = 1; a < d.dims_; ++a)
      if (box.hi[a] - box.lo[a] > box.hi[axis] - box.lo[axis]) axis = a;
    const int below_ranks = rank_count / 2;
    // The cut leaves below it the share of the points that its ranks should own.
    const std::size_t n = last - first;
    const std::size_t k = first + n * static_cast<std::size_t>(below_ranks) / static_cast<std::size_t>(rank_count);
    const auto begin = xs.begin() + static_cast<std::ptrdiff_t>(first), end = xs.begin() + static_cast<std::ptrdiff_t>(last);
    double at = 0.5 * (box.lo[axis] + box.hi[axis]);
    if (n > 0 && k > first && k < last) {
      std::nth_element(begin, xs.begin() + static_cast<std::ptrdiff_t>(k), end,
                       [axis](const auto& a, const auto& b) { return a[axis] < b[axis]; });
      at = xs[k][axis];
      // Points below the cut: those under `at`, or (the next value up) those at or under it,
      // whichever is nearer the share. A lattice's planes each hold many points: a sample's k-th
      // may lie on either side of a boundary, and the first choice alone put 49 of 100 planes
      // below a cut of 10^6 lattice points in two.
      std::size_t under = 0, at_or_under = 0;
      double next = std::numeric_limits<double>::infinity();
      for (auto x = begin; x != end; ++x) {
        const double v = (*x)[axis];
        under += v < at;
        at_or_under += v <= at;
        if (v > at) next = std::min(next, v);
      }
      const std::size_t share = k - first;
      if (next < std::numeric_limits<double>::infinity() && at_or_under - share < share - under) at = next;
    }
    at = std::clamp(at, box.lo[axis], box.hi[axis]);
    const std::size_t middle =  // points below the cut first
        first + static_cast<std::size_t>(std::partition(begin, end, [&](const auto& x) { return x[axis] < at; }) - begin);
    Box below = box, above = box;
    below.hi[axis] = above.lo[axis] = at;
    const int node = static_cast<int>(d.tree_.size());
    d.tree_.push_back({axis, at, 0, 0});
    const int b = self(self, below, first, middle, first_rank, below_ranks);
    const int a = self(self, above, middle, last, first_rank + below_ranks, rank_count - below_ranks);
    d.tree_[static_cast<std::size_t>(node)].below = b;
    d.tree_[static_cast<std::size_t>(node)].above = a;
    return node;
  };
  split(split, open_box(bounds, d.dims_), 0, sample.size(), 0, ranks);
  return d;
}

int Decomposition::owner(const double* x) const {
  if (tree_.empty()) return 0;
  int node = 0;
  for (;;) {
    const Cut& cut = tree_[static_cast<std::size_t>(node)];
    const int next = x[cut.axis] < cut.at ? cut.below : cut.above;
    if (next < 0) return -1 - next;
    node = next;
  }
}

int Decomposition::owner_and_near(const double* x, double reach, std::uint64_t& near) const {
  near = 0;
  if (tree_.empty()) return 0;
  const int owner = this->owner(x);
  // Farther than reach from every face of its own box, x is near no other box (their interiors
  // would overlap): most points, with no walk.
  const Box& own = box(owner);
  bool inside = true;
  for (int a = 0; a < dims_; ++a) inside &= x[a] > own.lo[a] + reach && x[a] < own.hi[a] - reach;
  if (inside) return owner;
  // A rank below a cut has hi <= at on its axis, one above lo >= at: x near its box needs
  // x < at + reach, or x > at - reach. Ranks past every such test get Box::near itself.
  int stack[64];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0) {
    const Cut& cut = tree_[static_cast<std::size_t>(stack[--depth])];
    const double at = x[cut.axis];
    for (const int next : {at < cut.at + reach ? cut.below : 0, at > cut.at - reach ? cut.above : 0}) {
      if (next > 0) {
        stack[depth++] = next;
      } else if (next < 0 && -1 - next != owner && box(-1 - next).near(x, dims_, reach)) {
        near |= std::uint64_t{1} << (-1 - next);
      }
    }
  }
  return owner;
}

std::vector<int> Decomposition::partners(int rank, double reach) const {
  std::vector<int> out;
  const Box& mine = box(rank);
  for (int r = 0; r < ranks(); ++r) {
    if (r == rank) continue;
    const Box& other = box(r);
    bool overlaps = true;
    for (int a = 0; a < dims_; ++a)
      overlaps = overlaps && other.lo[a] - reach < mine.hi[a] && mine.lo[a] < other.hi[a] + reach;
    if (overlaps) out.push_back(r);
  }
  return out;
}

}  // namespace horizon
