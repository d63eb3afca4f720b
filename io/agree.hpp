#pragma once
// How the writer's ranks fail together: a step that may throw on some ranks only is turned into
// one that throws the same DatasetError on every rank, so that no rank is left waiting in a
// later collective call.
#include <mpi.h>

#include <functional>

namespace grip::io {

// Runs `step`, which makes no collective call; if it throws on any rank, every rank throws the
// message of the lowest failing rank.
void agree(MPI_Comm comm, const std::function<void()>& step);

}  // namespace grip::io
