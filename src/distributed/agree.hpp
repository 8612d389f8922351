#pragma once
// Failures that only some ranks see (a bad point, a full disk) become one error on every rank,
// so that no rank is left waiting in a collective the others never reach.
#include <mpi.h>

#include <string>

namespace horizon::detail {

/// Collective: returns when `failure` is empty on every rank; else throws CollectiveError on
/// every rank with the first failing rank's message.
void agree(MPI_Comm comm, const std::string& failure);

}  // namespace horizon::detail
