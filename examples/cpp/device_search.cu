// Points that live on the GPU: the list is built there and stays there (no host copy).
#include <cuda_runtime.h>

#include <cstdio>

#include <horizon/cuda.hpp>
#include <horizon/generate.hpp>

int main() {
  if (horizon::cuda_device_count() == 0) {
    std::printf("no GPU: nothing to show\n");
    return 0;
  }
  const horizon::PointSet points = horizon::lattice(50);  // 125,000 points
  double* xyz = nullptr;
  cudaMalloc(&xyz, points.xyz.size() * sizeof(double));
  cudaMemcpy(xyz, points.xyz.data(), points.xyz.size() * sizeof(double), cudaMemcpyHostToDevice);
  cudaStream_t stream;
  cudaStreamCreate(&stream);
  horizon::SearchOptions options;
  options.horizon = 3.015 * 10.0 / 50;
  {
    horizon::DeviceNeighborList list = horizon::search_device(xyz, points.size(), 3, options, stream);
    // list.offsets() and list.indices() are device pointers: hand them to your kernels on `stream`.
    std::printf("%lld entries on %s\n", static_cast<long long>(list.total()), horizon::cuda_device_name(0).c_str());
    if (list.total() != horizon::lattice_entries(50, 3, 3.015)) return 1;
  }  // the list's memory goes back to horizon's pool, ordered on `stream`
  cudaStreamDestroy(stream);
  cudaFree(xyz);
  return 0;
}
