#pragma once
// Included by the CUDA translation units: definitions in an anonymous namespace.
// Launch shape and error check shared by the CUDA backend's kernels.
#include <cuda_runtime.h>

#include <cstddef>

#include "device_memory.hpp"

namespace horizon::detail {
namespace {

constexpr int block_size = 256;

unsigned blocks_for(std::size_t threads) {
  return static_cast<unsigned>((threads + block_size - 1) / block_size);
}

void check_launch(const char* kernel) {
  cuda_check(cudaGetLastError(), kernel, __FILE__, __LINE__);
}

}  // namespace
}  // namespace horizon::detail
