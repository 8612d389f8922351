#pragma once
// The fuzzed bytes as a file: horizon's readers take paths, so every input is written to a
// scratch file (in /dev/shm when there is one) and read back through the public API.
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace horizon::fuzz {

class ScratchDirectory {
public:
  ScratchDirectory() {
    const char* base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    path_ = std::string(base) + "/horizon_fuzz_" + std::to_string(getpid());
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }

private:
  std::string path_;
};

/// The path of the scratch file `name` (the directory is removed at exit).
inline std::string scratch_path(const std::string& name) {
  static const ScratchDirectory directory;
  return directory.path() + "/" + name;
}

/// Writes `size` bytes to the scratch file `name` and returns its path.
inline std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch_path(name);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr || (size > 0 && std::fwrite(data, 1, size, file) != size) || std::fclose(file) != 0) {
    std::perror(path.c_str());
    std::abort();
  }
  return path;
}

/// A broken invariant in what a reader returned: a defect, reported as a crash.
inline void require(bool holds, const char* what) {
  if (!holds) {
    std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
    std::abort();
  }
}

}  // namespace horizon::fuzz
