#include "bench/ccd/ccd_query_file.hpp"

#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "bench/ccd/exact_separation.hpp"

namespace grip::bench {

namespace {

constexpr int kColumns = 7;
constexpr const char* kRowFormat = "x_num,x_den,y_num,y_den,z_num,z_den,truth";

[[noreturn]] void fail(const std::filesystem::path& path, std::size_t line,
                       const std::string& message) {
  throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": " + message);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

bool is_integer(std::string_view s) {
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) s.remove_prefix(1);
  if (s.empty()) return false;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

mpz_class parse_integer(std::string_view field) {
  if (field.front() == '+') field.remove_prefix(1);
  return mpz_class(std::string(field), 10);
}

}  // namespace

std::vector<CcdQuery> read_ccd_query_file(const std::filesystem::path& path, CcdQueryType type) {
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error(path.string() + ": cannot open the CCD query file; check the path");
  }
  std::vector<CcdQuery> queries;
  RationalCcdQuery current;
  std::size_t rows_in_query = 0;
  std::size_t first_line_of_query = 0;
  std::size_t line_number = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++line_number;
    if (trim(line).empty()) continue;  // blank lines (e.g. a trailing newline) carry nothing
    std::string_view fields[kColumns];
    int count = 0;
    std::string_view rest(line);
    while (true) {
      const std::size_t comma = rest.find(',');
      if (count < kColumns) fields[count] = trim(rest.substr(0, comma));
      ++count;
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    if (count != kColumns) {
      fail(path, line_number,
           "expected " + std::to_string(kColumns) + " comma-separated columns (" + kRowFormat +
               "), found " + std::to_string(count));
    }
    for (int column = 0; column < kColumns; ++column) {
      if (!is_integer(fields[column])) {
        fail(path, line_number,
             "column " + std::to_string(column + 1) + " is '" + std::string(fields[column]) +
                 "', not an integer (rows are " + kRowFormat + ")");
      }
    }
    if (rows_in_query == 0) first_line_of_query = line_number;
    for (int axis = 0; axis < 3; ++axis) {
      const mpz_class den = parse_integer(fields[2 * axis + 1]);
      if (den == 0) {
        fail(path, line_number,
             "column " + std::to_string(2 * axis + 2) + " is a zero denominator");
      }
      mpq_class value(parse_integer(fields[2 * axis]), den);
      value.canonicalize();
      current.vertices[rows_in_query][axis] = value;
    }
    const std::string_view truth = fields[6];
    if (truth != "0" && truth != "1") {
      fail(path, line_number,
           "the truth column (7) is '" + std::string(truth) + "'; it must be 0 or 1");
    }
    const bool collides = truth == "1";
    if (rows_in_query == 0) {
      current.collides = collides;
    } else if (collides != current.collides) {
      fail(path, line_number,
           "truth " + std::string(truth) +
               " differs from the truth of this query's first row (line " +
               std::to_string(first_line_of_query) + "); all 8 rows of a query share one truth");
    }
    if (++rows_in_query == kCcdQueryRows) {
      queries.push_back(to_double_query(current));
      queries.back().touches_at_start = exactly_touching_at_start(current, type);
      rows_in_query = 0;
    }
  }
  if (rows_in_query != 0) {
    fail(path, line_number,
         "the file ends inside a query (" + std::to_string(rows_in_query) +
             " of 8 rows since line " + std::to_string(first_line_of_query) +
             "); a query is 8 rows, so the row count must be a multiple of 8");
  }
  return queries;
}

void write_ccd_query_file(const std::filesystem::path& path,
                          const std::vector<RationalCcdQuery>& queries) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  for (const RationalCcdQuery& query : queries) {
    for (const auto& vertex : query.vertices) {
      for (int axis = 0; axis < 3; ++axis) {
        mpq_class value = vertex[axis];
        value.canonicalize();
        out << value.get_num().get_str() << ',' << value.get_den().get_str() << ',';
      }
      out << (query.collides ? 1 : 0) << '\n';
    }
  }
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": writing failed (disk full?)");
}

}  // namespace grip::bench
