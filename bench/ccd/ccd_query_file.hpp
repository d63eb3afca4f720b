#pragma once
// Reading and writing the rational CSV format of the CCD benchmark (Wang et al. 2021): 8 rows
// per query, each row "x_num,x_den,y_num,y_den,z_num,z_den,truth" with arbitrary-size integers
// and truth 0 or 1, the same on all 8 rows of a query.
#include <filesystem>
#include <vector>

#include "bench/ccd/ccd_query.hpp"

namespace grip::bench {

// Parses the integers exactly (GMP) and rounds each coordinate to the nearest double; marks
// the queries of `type` whose exact primitives touch at t = 0 (CcdQuery::touches_at_start).
// Throws std::runtime_error "FILE:LINE: what is wrong; what to do" on a malformed file.
std::vector<CcdQuery> read_ccd_query_file(const std::filesystem::path& path, CcdQueryType type);

// Writes queries in the same format (numerators and denominators in lowest terms).
// Throws std::runtime_error naming the file if it cannot be written.
void write_ccd_query_file(const std::filesystem::path& path,
                          const std::vector<RationalCcdQuery>& queries);

}  // namespace grip::bench
