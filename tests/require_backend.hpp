#pragma once
// Skips a test whose backend this build or machine lacks, unless HORIZON_REQUIRE_GPU=1 demands
// the GPU. Call from the test body, then return if skipped or failed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "horizon/search.hpp"

namespace horizon::testing {

inline void require(Backend backend) {
  if (backend_available(backend)) return;
  const char* required = std::getenv("HORIZON_REQUIRE_GPU");
  if (backend == Backend::cuda && required && std::string(required) == "1")
    FAIL() << "HORIZON_REQUIRE_GPU=1 but the cuda backend is not usable";
  GTEST_SKIP() << "backend " << backend_name(backend) << " is not available here (no GPU)";
}

}  // namespace horizon::testing
