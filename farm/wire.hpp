#pragma once
// Byte strings for what one rank computes and every rank needs (prepared objects, synthesized
// candidates), and their broadcast. Doubles travel bit for bit, so every rank holds exactly
// what the computing rank made.
#include <mpi.h>

#include <string>
#include <string_view>
#include <vector>

#include "io/object_record.hpp"
#include "src/synth/candidate.hpp"

namespace grip::farm {

std::string pack(const io::ObjectRecord& record);
io::ObjectRecord unpack_object(std::string_view bytes);

std::string pack(const std::vector<synth::Candidate>& candidates);
std::vector<synth::Candidate> unpack_candidates(std::string_view bytes);

// Collective: every rank of `comm` ends with root's `bytes`.
void broadcast(std::string& bytes, int root, MPI_Comm comm);

// Collective: the error of the lowest rank whose `error` is not empty, on every rank ("" when
// none failed), so that all ranks stop alike rather than leave others waiting in a collective.
std::string first_error(const std::string& error, MPI_Comm comm);

}  // namespace grip::farm
