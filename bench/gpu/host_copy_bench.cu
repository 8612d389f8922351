// Device -> fresh pageable host memory: which way of copying a neighbour list out reaches PCIe
// speed on this machine? Each variant copies the same device bytes into a new malloc'd buffer
// (never touched before, as a freshly built list is) and is timed end to end, faults included.
// Standalone (CUDA + OpenMP only):
//   nvcc -O3 -arch=sm_90 -Xcompiler -fopenmp bench/gpu/host_copy_bench.cu -o host_copy_bench
//   ./host_copy_bench GIB...
#include <cuda_runtime.h>
#include <immintrin.h>
#include <omp.h>
#include <sys/mman.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#define CHECK(call) \
  do { \
    cudaError_t status_ = (call); \
    if (status_ != cudaSuccess) { \
      std::fprintf(stderr, "%s:%d %s\n", __FILE__, __LINE__, cudaGetErrorString(status_)); \
      std::exit(1); \
    } \
  } while (0)

namespace {

constexpr std::size_t staging_bytes = std::size_t{64} << 20;
constexpr std::size_t page = 4096;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

void touch(char* p, std::size_t bytes) {
  const auto pages = static_cast<long>((bytes + page - 1) / page);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < pages; ++i) p[i * page] = 0;
}

void copy_temporal(char* to, const char* from, std::size_t bytes) {
  constexpr std::size_t piece = std::size_t{1} << 20;
  const auto pieces = static_cast<long>((bytes + piece - 1) / piece);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < pieces; ++i) {
    const std::size_t at = i * piece;
    std::memcpy(to + at, from + at, std::min(piece, bytes - at));
  }
}

// Non-temporal stores: no read-for-ownership of the destination (bytes multiple of 64, aligned).
void copy_streaming(char* to, const char* from, std::size_t bytes) {
  constexpr std::size_t piece = std::size_t{1} << 20;
  const auto pieces = static_cast<long>((bytes + piece - 1) / piece);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < pieces; ++i) {
    const std::size_t at = i * piece, size = std::min(piece, bytes - at);
    auto* d = reinterpret_cast<__m256i*>(to + at);
    auto* s = reinterpret_cast<const __m256i*>(from + at);
    for (std::size_t k = 0; k < size / 32; ++k) _mm256_stream_si256(d + k, _mm256_load_si256(s + k));
  }
  _mm_sfence();
}

struct Staged {
  char* buffer = nullptr;
  cudaEvent_t done[2];
  Staged() {
    CHECK(cudaHostAlloc(reinterpret_cast<void**>(&buffer), 2 * staging_bytes, cudaHostAllocDefault));
    for (auto& e : done) CHECK(cudaEventCreateWithFlags(&e, cudaEventDisableTiming));
  }
};

void staged_copy(Staged& s, char* host, const char* device, std::size_t bytes, cudaStream_t stream,
                 void (*copy)(char*, const char*, std::size_t)) {
  const std::size_t chunks = (bytes + staging_bytes - 1) / staging_bytes;
  auto issue = [&](std::size_t c) {
    const std::size_t at = c * staging_bytes, size = std::min(staging_bytes, bytes - at);
    CHECK(cudaMemcpyAsync(s.buffer + (c % 2) * staging_bytes, device + at, size, cudaMemcpyDeviceToHost, stream));
    CHECK(cudaEventRecord(s.done[c % 2], stream));
  };
  issue(0);
  for (std::size_t c = 0; c < chunks; ++c) {
    if (c + 1 < chunks) issue(c + 1);
    CHECK(cudaEventSynchronize(s.done[c % 2]));
    const std::size_t at = c * staging_bytes, size = std::min(staging_bytes, bytes - at);
    copy(host + at, s.buffer + (c % 2) * staging_bytes, size);
  }
}

// Register the destination a piece at a time and DMA straight into it; the next piece is
// touched and registered while the previous one's copy runs.
void registered_copy(char* host, const char* device, std::size_t bytes, std::size_t piece, cudaStream_t stream) {
  std::vector<char*> registered;
  for (std::size_t at = 0; at < bytes; at += piece) {
    const std::size_t size = std::min(piece, bytes - at);
    touch(host + at, size);
    CHECK(cudaHostRegister(host + at, size, cudaHostRegisterDefault));
    registered.push_back(host + at);
    CHECK(cudaMemcpyAsync(host + at, device + at, size, cudaMemcpyDeviceToHost, stream));
  }
  CHECK(cudaStreamSynchronize(stream));
  for (char* p : registered) CHECK(cudaHostUnregister(p));
}

char* fresh(std::size_t bytes, bool huge) {
  void* p = nullptr;
  if (posix_memalign(&p, std::size_t{2} << 20, bytes)) std::exit(1);
  if (huge) madvise(p, bytes, MADV_HUGEPAGE);
  return static_cast<char*>(p);
}

std::string read_file(const char* path) {
  std::FILE* f = std::fopen(path, "r");
  if (!f) return "?";
  char line[256] = {};
  if (!std::fgets(line, sizeof line, f)) line[0] = 0;
  std::fclose(f);
  std::string s(line);
  if (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

// SKIP="register,pageable" leaves out the variants whose names contain one of those words.
bool skipped(const std::string& name) {
  const char* skip = std::getenv("SKIP");
  if (!skip) return false;
  std::string words = std::string(skip) + ",";
  for (std::size_t at = 0, comma; (comma = words.find(',', at)) != std::string::npos; at = comma + 1)
    if (comma > at && name.find(words.substr(at, comma - at)) != std::string::npos) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atof(argv[i]));
  if (sizes.empty()) sizes = {4, 16};
  cudaDeviceProp prop{};
  CHECK(cudaGetDeviceProperties(&prop, 0));
  std::printf("# %s, %d host threads, THP enabled: %s, defrag: %s\n", prop.name, omp_get_max_threads(),
              read_file("/sys/kernel/mm/transparent_hugepage/enabled").c_str(),
              read_file("/sys/kernel/mm/transparent_hugepage/defrag").c_str());
  std::printf("gib,variant,seconds,gb_per_s,vs_pinned\n");
  cudaStream_t stream;
  CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  Staged staged;
  for (double gib : sizes) {
    const std::size_t bytes = static_cast<std::size_t>(gib * (1 << 30)) / 64 * 64;
    char* device = nullptr;
    CHECK(cudaMalloc(&device, bytes));
    CHECK(cudaMemset(device, 7, bytes));
    char* pinned = nullptr;
    double t = now();
    CHECK(cudaHostAlloc(reinterpret_cast<void**>(&pinned), bytes, cudaHostAllocDefault));
    const double pin_alloc = now() - t;
    CHECK(cudaMemcpy(pinned, device, bytes, cudaMemcpyDeviceToHost));  // warm
    t = now();
    CHECK(cudaMemcpy(pinned, device, bytes, cudaMemcpyDeviceToHost));
    const double floor = now() - t;
    auto report = [&](const char* name, double s) {
      std::printf("%.1f,%s,%.4f,%.1f,%.2f\n", gib, name, s, bytes / s / 1e9, s / floor);
      std::fflush(stdout);
    };
    report("pinned_floor", floor);
    report("cudaHostAlloc_of_the_list", pin_alloc);
    CHECK(cudaFreeHost(pinned));

    struct Variant {
      const char* name;
      bool huge;
      std::function<void(char*)> run;
    };
    const std::vector<Variant> variants = {
        {"cudaMemcpy_pageable", false, [&](char* h) { CHECK(cudaMemcpy(h, device, bytes, cudaMemcpyDeviceToHost)); }},
        {"touch+staged_memcpy", false,
         [&](char* h) { touch(h, bytes); staged_copy(staged, h, device, bytes, stream, copy_temporal); }},
        {"staged_memcpy_faulting", false, [&](char* h) { staged_copy(staged, h, device, bytes, stream, copy_temporal); }},
        {"touch+staged_stream", false,
         [&](char* h) { touch(h, bytes); staged_copy(staged, h, device, bytes, stream, copy_streaming); }},
        {"staged_stream_faulting", false, [&](char* h) { staged_copy(staged, h, device, bytes, stream, copy_streaming); }},
        {"thp+staged_stream_faulting", true,
         [&](char* h) { staged_copy(staged, h, device, bytes, stream, copy_streaming); }},
        {"thp+touch+staged_stream", true,
         [&](char* h) { touch(h, bytes); staged_copy(staged, h, device, bytes, stream, copy_streaming); }},
        {"register_whole", false, [&](char* h) { registered_copy(h, device, bytes, bytes, stream); }},
        {"register_256MiB_pieces", false, [&](char* h) { registered_copy(h, device, bytes, std::size_t{256} << 20, stream); }},
        {"thp+register_256MiB_pieces", true,
         [&](char* h) { registered_copy(h, device, bytes, std::size_t{256} << 20, stream); }},
        {"thp+register_whole", true, [&](char* h) { registered_copy(h, device, bytes, bytes, stream); }},
        {"thp+touch_only", true, [&](char* h) { touch(h, bytes); }},
        {"touch_only", false, [&](char* h) { touch(h, bytes); }},
    };
    // The copy alone, into memory faulted in beforehand (as while the GPU computes), and the
    // host's own copy bandwidth between two faulted-in buffers: the bound of any staged copy.
    const std::vector<Variant> prefaulted = {
        {"prefaulted_thp+staged_stream", true, [&](char* h) { staged_copy(staged, h, device, bytes, stream, copy_streaming); }},
        {"prefaulted_thp+staged_memcpy", true, [&](char* h) { staged_copy(staged, h, device, bytes, stream, copy_temporal); }},
        {"prefaulted+staged_stream", false, [&](char* h) { staged_copy(staged, h, device, bytes, stream, copy_streaming); }},
        {"prefaulted_thp+host_stream_copy", true, [&](char* h) { copy_streaming(h, h + bytes / 2, bytes / 2 / 64 * 64); }},
        {"prefaulted_thp+host_stream_write", true, [&](char* h) {
           const auto blocks = static_cast<long>(bytes / 32);
#pragma omp parallel for schedule(static)
           for (long k = 0; k < blocks; ++k) _mm256_stream_si256(reinterpret_cast<__m256i*>(h) + k, _mm256_set1_epi8(7));
           _mm_sfence();
         }},
    };
    for (int rep = 0; rep < 2; ++rep)
      for (const auto& v : prefaulted) {
        char* h = fresh(bytes, v.huge);
        touch(h, bytes);
        std::memset(h + bytes / 2, 7, bytes - bytes / 2);
        t = now();
        v.run(h);
        const double s = now() - t;
        const bool ok = h[0] == 7 && h[bytes - 1] == 7;
        std::free(h);
        if (!ok) { std::printf("# %s: wrong bytes\n", v.name); return 1; }
        if (rep == 1) report(v.name, s);
      }
    for (int rep = 0; rep < 2; ++rep)
      for (const auto& v : variants) {
        if (skipped(v.name)) continue;
        char* h = fresh(bytes, v.huge);
        t = now();
        v.run(h);
        const double s = now() - t;
        const bool ok = v.name == std::string("thp+touch_only") || v.name == std::string("touch_only") ||
                        (h[0] == 7 && h[bytes - 1] == 7 && h[bytes / 2] == 7);
        std::free(h);
        if (!ok) { std::printf("# %s: wrong bytes\n", v.name); return 1; }
        if (rep == 1) report(v.name, s);
      }
    CHECK(cudaFree(device));
  }
}
