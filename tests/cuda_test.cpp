// The CUDA backend's own entry points: device-resident search, batched host search, errors.
// The oracle cases for the cuda backend are in oracle_test.cpp.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "horizon/cuda.hpp"
#include "horizon/generate.hpp"
#include "horizon/search.hpp"

#if defined(HORIZON_WITH_CUDA)
#include <cuda_runtime.h>
#endif

namespace horizon {
namespace {

bool gpu_present() {
  if (backend_available(Backend::cuda)) return true;
  const char* required = std::getenv("HORIZON_REQUIRE_GPU");
  if (required && std::string(required) == "1") ADD_FAILURE() << "HORIZON_REQUIRE_GPU=1 but no usable GPU";
  return false;
}

#define REQUIRE_GPU() \
  if (!gpu_present()) GTEST_SKIP() << "no usable GPU: cuda backend not tested here"

SearchOptions options_for(double horizon, Backend backend) {
  SearchOptions options;
  options.horizon = horizon;
  options.backend = backend;
  return options;
}

TEST(Cuda, BatchedHostSearchEqualsSerial) {
  REQUIRE_GPU();
  const PointSet points = clustered_cloud(200000, 30, 0.4, 3, 5);
  SearchOptions cuda = options_for(0.1, Backend::cuda);
  cuda.gpu_batch_entries = 100000;  // many batches
  EXPECT_EQ(search(points.view(), cuda), search(points.view(), options_for(0.1, Backend::serial)));
}

TEST(Cuda, RowsOfEveryLengthAreSorted) {
  REQUIRE_GPU();
  // Families of ~50 and ~100 (warp sorts), ~1000 (block sort), ~3000 (segmented sort) points.
  for (std::size_t blob : {50u, 100u, 1000u, 3000u}) {
    PointSet points = clustered_cloud(blob, 1, 0.01, 3, 4);
    const PointSet spread = random_cloud(5000, 3, 6);
    points.xyz.insert(points.xyz.end(), spread.xyz.begin(), spread.xyz.end());
    EXPECT_EQ(search(points.view(), options_for(0.5, Backend::cuda)),
              search(points.view(), options_for(0.5, Backend::serial)))
        << blob;
  }
}

TEST(Cuda, QueriesMatchTheCpu) {
  REQUIRE_GPU();
  const PointSet points = random_cloud(30000, 3, 2);
  SearchOptions cuda = options_for(0.5, Backend::cuda), cpu = options_for(0.5, Backend::serial);
  cuda.queries = cpu.queries = 12345;
  EXPECT_EQ(search(points.view(), cuda), search(points.view(), cpu));
}

TEST(Cuda, LatticeMatchesClosedFormAtScale) {
  REQUIRE_GPU();
  for (double m : {1.5, 3.015}) {
    const PointSet points = lattice(100);
    SearchStats stats;
    const NeighborList list = search(points.view(), options_for(m * 0.1, Backend::cuda), &stats);
    EXPECT_EQ(list.total(), lattice_entries(100, 3, m));
    EXPECT_FALSE(stats.gpu_name.empty());
    EXPECT_GT(stats.peak_gpu_bytes, 0u);
  }
}

#if defined(HORIZON_WITH_CUDA)
TEST(Cuda, DeviceResidentSearchEqualsHostSearch) {
  REQUIRE_GPU();
  for (int dims : {2, 3}) {
    const PointSet points = random_cloud(50000, dims, 9);
    const double horizon = dims == 3 ? 0.5 : 0.08;
    double* device_xyz = nullptr;
    ASSERT_EQ(cudaMalloc(&device_xyz, points.xyz.size() * sizeof(double)), cudaSuccess);
    ASSERT_EQ(cudaMemcpy(device_xyz, points.xyz.data(), points.xyz.size() * sizeof(double), cudaMemcpyHostToDevice),
              cudaSuccess);
    cudaStream_t stream;
    ASSERT_EQ(cudaStreamCreate(&stream), cudaSuccess);
    for (bool half : {false, true}) {
      SearchOptions options = options_for(horizon, Backend::serial);
      options.half = half;
      const DeviceNeighborList on_gpu = search_device(device_xyz, points.size(), dims, options, stream);
      ASSERT_EQ(cudaStreamSynchronize(stream), cudaSuccess);
      EXPECT_EQ(on_gpu.to_host(half), search(points.view(), options));
    }
    cudaStreamDestroy(stream);
    cudaFree(device_xyz);
  }
}

TEST(Cuda, ErrorsAreClear) {
  REQUIRE_GPU();
  const PointSet points = random_cloud(10, 3, 1);
  SearchOptions options = options_for(1.0, Backend::cuda);
  options.device = 999;
  try {
    search(points.view(), options);
    FAIL() << "device 999 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("device 999"), std::string::npos) << e.what();
  }
}
#endif

TEST(Cuda, UnavailableBackendIsAnError) {
  if (backend_available(Backend::cuda)) GTEST_SKIP() << "a GPU is present";
  const PointSet points = random_cloud(10, 3, 1);
  EXPECT_THROW(search(points.view(), options_for(1.0, Backend::cuda)), Error);
}

}  // namespace
}  // namespace horizon
