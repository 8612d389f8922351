#pragma once
// A file written under a temporary name and renamed into place by commit(); destroyed
// uncommitted, the temporary is removed. Throws horizon::Error naming the path on failure.
#include <cstdio>
#include <string>

namespace horizon::detail {

class AtomicFile {
public:
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(const void* data, std::size_t bytes);
  void write(const std::string& text) { write(text.data(), text.size()); }
  void commit();

private:
  std::string path_, temporary_;
  std::FILE* file_ = nullptr;
};

}  // namespace horizon::detail
