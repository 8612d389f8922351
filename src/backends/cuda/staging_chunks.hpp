#pragma once
// How a copy through pinned staging is cut into chunks (host_copy.cuh; plain C++, so that the
// CPU tests check it).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace horizon::detail {

/// Bytes [at, at + size) of a copy through staging.
struct StagedChunk {
  std::size_t at, size;
};

/// The chunks of a `bytes` copy through staging buffers of `largest` bytes: `largest` each in
/// the middle, halving towards both ends down to 2 MB. At either end one stage waits for the
/// other (the DMA for the cores' first chunk, or the cores for the DMA's; and the last chunk's
/// second stage runs alone), so small end chunks shorten both waits, and large middle ones keep
/// the per-chunk costs (a DMA call, an event, the cores' fork and join) down.
/// H100 machine's 16-core Xeon host, host->host lattice 100 at m = 1.5: 4.4 -> 3.8 ms (h2d 1.05
/// -> 0.7 ms, d2h 2.7 -> 2.5); larger lists, bound by the host's memory traffic, unchanged
/// (bench/results/staging_ramp_1206/).
inline std::vector<StagedChunk> staging_chunks(std::size_t bytes, std::size_t largest) {
  constexpr std::size_t end_chunk = std::size_t{2} << 20;
  std::vector<std::size_t> front, back;
  std::size_t left = bytes;
  for (std::size_t step = std::min(end_chunk, largest); left > 0; step = std::min(2 * step, largest)) {
    for (auto* end : {&front, &back}) {
      const std::size_t size = std::min(step, left);
      if (size == 0) break;
      end->push_back(size);
      left -= size;
    }
  }
  front.insert(front.end(), back.rbegin(), back.rend());
  std::vector<StagedChunk> chunks;
  std::size_t at = 0;
  for (const std::size_t size : front) {
    chunks.push_back({at, size});
    at += size;
  }
  return chunks;
}

}  // namespace horizon::detail
