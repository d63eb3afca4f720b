#pragma once
// Whether two trial results are the same apart from wall time: what "a batch gives the same
// verdicts and metrics as solo runs, for any thread count" means, checked bit for bit
// (NaN matches NaN: unreached phases' displacements, D1/D2 of a failed trial).
#include "io/candidate_record.hpp"

namespace grip::trial {

bool same_result(const io::CandidateResult& a, const io::CandidateResult& b);

}  // namespace grip::trial
