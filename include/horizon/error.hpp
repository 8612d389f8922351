#pragma once
/// \file error.hpp
/// The one exception type horizon throws for bad input and failed resources.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace horizon {

/// Thrown for anything the caller can fix: bad coordinates, a bad horizon, a malformed file,
/// an unwritable output. The message names the file, line or point index at fault.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Thrown before the list is allocated when it would not fit in host memory (the memory
/// available, or SearchOptions::max_memory); the message gives the size and the ways out.
class ListTooLarge : public Error {
public:
  ListTooLarge(const std::string& what, std::size_t needed, std::size_t available)
      : Error(what), bytes_needed(needed), bytes_available(available) {}
  std::size_t bytes_needed, bytes_available;
};

/// Thrown alike on every rank of a collective operation (the distributed writer) once the ranks
/// agreed that one of them failed: no rank is left waiting, so no abort is needed.
class CollectiveError : public Error {
public:
  using Error::Error;
};

}  // namespace horizon
