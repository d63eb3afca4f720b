// The CCD benchmark's rational CSV format: exact parsing and rounding to nearest, a round trip
// through the writer, touching starts found exactly, and one clear error (file and line) per
// kind of malformed file.
#include "bench/ccd/ccd_query_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "bench/ccd/exact_separation.hpp"

namespace {

using grip::bench::CcdQuery;
using grip::bench::CcdQueryType;
using grip::bench::collides_in_truth;
using grip::bench::exactly_separated_at;
using grip::bench::RationalCcdQuery;
using grip::bench::read_ccd_query_file;
using grip::bench::write_ccd_query_file;

std::filesystem::path temp_file(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "grip_ccd_query_file";
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::filesystem::path write_text(const std::string& name, const std::string& text) {
  const auto path = temp_file(name);
  std::ofstream(path) << text;
  return path;
}

std::string rows(int count, const std::string& row) {
  std::string text;
  for (int i = 0; i < count; ++i) text += row + "\n";
  return text;
}

// The message of the error read_ccd_query_file throws, or "" if it throws none.
std::string read_error(const std::filesystem::path& path) {
  try {
    read_ccd_query_file(path, CcdQueryType::kVertexFace);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(CcdQueryFile, ParsesExactRationalsAndRoundsToNearest) {
  // Integers far beyond 64 bits parse exactly: (2^200 + 1) / 2^200 rounds to 1. Rounding is to
  // nearest, not toward zero: 1/10 is 0.1 (truncation would give the double just below it).
  const std::string two200 = "1606938044258990275541962092341162602522202993782792835301376";
  const std::string two200_plus_one = two200.substr(0, two200.size() - 1) + "7";
  std::string text = two200_plus_one + "," + two200 + ",1,10,1,-2,0\n";
  text += "-1,10,-7,1,123456789012345678901234567890,1,0\n";
  text += rows(6, "0,1,0,1,0,1,0");
  const auto path = write_text("exact.csv", text);
  const std::vector<CcdQuery> queries = read_ccd_query_file(path, CcdQueryType::kVertexFace);
  ASSERT_EQ(queries.size(), 1u);
  EXPECT_EQ(queries[0].vertices[0].x(), 1.0);
  EXPECT_EQ(queries[0].vertices[0].y(), 0.1);
  EXPECT_EQ(queries[0].vertices[0].z(), -0.5);
  EXPECT_EQ(queries[0].vertices[1].x(), -0.1);
  EXPECT_EQ(queries[0].vertices[1].y(), -7.0);
  EXPECT_EQ(queries[0].vertices[1].z(), 1.2345678901234568e29);
  EXPECT_FALSE(queries[0].collides);
}

TEST(CcdQueryFile, RoundTripsThroughTheWriter) {
  std::vector<RationalCcdQuery> written(3);
  for (std::size_t q = 0; q < written.size(); ++q) {
    for (std::size_t row = 0; row < grip::bench::kCcdQueryRows; ++row) {
      for (int axis = 0; axis < 3; ++axis) {
        written[q].vertices[row][axis] =
            mpq_class(static_cast<long>(q * 100 + row * 10 + axis) - 50, 7 + axis);
      }
    }
    written[q].collides = q % 2 == 1;
  }
  const auto path = temp_file("round_trip.csv");
  write_ccd_query_file(path, written);
  const std::vector<CcdQuery> read = read_ccd_query_file(path, CcdQueryType::kVertexFace);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t q = 0; q < written.size(); ++q) {
    const CcdQuery expected = grip::bench::to_double_query(written[q]);
    EXPECT_EQ(read[q].collides, written[q].collides);
    for (std::size_t row = 0; row < grip::bench::kCcdQueryRows; ++row) {
      EXPECT_EQ(read[q].vertices[row], expected.vertices[row]);
    }
  }
}

// A query whose rational primitives touch at t = 0 is marked touching even where its doubles
// are apart and its label says 0; it then counts as a collision. The point (1/5, 3/5, 1/5) lies
// on the triangle (0,0,0), (1,0,0), (0,3,1) (the plane z = y / 3); rounded to doubles it is off.
TEST(CcdQueryFile, MarksTouchingStartsExactly) {
  auto query = [](const std::string& p0, const std::string& p1) {
    const std::string triangle = "\n0,1,0,1,0,1,0\n1,1,0,1,0,1,0\n0,1,3,1,1,1,0\n";
    return p0 + triangle + p1 + triangle;
  };
  // On the face and moving away; 1/20 above it (in z) and moving away.
  const auto vf = write_text("touching_vf.csv", query("1,5,3,5,1,5,0", "1,5,3,5,1,1,0") +
                                                    query("1,5,3,5,1,4,0", "1,5,3,5,1,1,0"));
  const std::vector<CcdQuery> queries = read_ccd_query_file(vf, CcdQueryType::kVertexFace);
  ASSERT_EQ(queries.size(), 2u);
  EXPECT_TRUE(queries[0].touches_at_start);
  EXPECT_TRUE(exactly_separated_at(queries[0], CcdQueryType::kVertexFace, 0.0, 0.0));
  EXPECT_FALSE(queries[0].collides);  // the label as read
  EXPECT_TRUE(collides_in_truth(queries[0]));
  EXPECT_FALSE(queries[1].touches_at_start);
  EXPECT_FALSE(collides_in_truth(queries[1]));

  // Edge-edge: (-1/3, 1/3, 0)-(1, 1/3, 0) crosses (1/3, 0, 0)-(1/3, 1, 0) at (1/3, 1/3, 0);
  // the same rows read as vertex-face do not touch (the point (-1/3, 1/3, 0) is off).
  std::string ee;
  for (int half = 0; half < 2; ++half) {
    ee +=
        "-1,3,1,3,0,1,1\n1,1,1,3,0,1,1\n1,3,0,1,0,1,1\n1,3,1,1," + std::to_string(half) + ",1,1\n";
  }
  const auto path = write_text("touching_ee.csv", ee);
  EXPECT_TRUE(read_ccd_query_file(path, CcdQueryType::kEdgeEdge)[0].touches_at_start);
  EXPECT_FALSE(read_ccd_query_file(path, CcdQueryType::kVertexFace)[0].touches_at_start);
}

TEST(CcdQueryFile, MalformedFilesNameTheFileAndLine) {
  const std::string good = "1,2,3,4,5,6,1";
  struct Bad {
    std::string name;
    std::string text;
    std::string where;  // "file:line"
    std::string what;   // a phrase the message must contain
  };
  const Bad cases[] = {
      {"columns.csv", rows(2, good) + "1,2,3,4,5,6\n" + rows(5, good),
       "columns.csv:3:", "expected 7 comma-separated columns"},
      {"extra.csv", rows(7, good) + "1,2,3,4,5,6,1,9\n", "extra.csv:8:", "found 8"},
      {"float.csv", good + "\n1.5,2,3,4,5,6,1\n" + rows(6, good), "float.csv:2:", "not an integer"},
      {"empty_field.csv", good + "\n1,,3,4,5,6,1\n" + rows(6, good),
       "empty_field.csv:2:", "not an integer"},
      {"zero.csv", rows(4, good) + "1,2,3,0,5,6,1\n" + rows(3, good),
       "zero.csv:5:", "zero denominator"},
      {"rows.csv", rows(12, good), "rows.csv:12:", "multiple of 8"},
      {"truth.csv", rows(3, good) + "1,2,3,4,5,6,0\n" + rows(4, good),
       "truth.csv:4:", "differs from the truth of this query's first row (line 1)"},
      {"truth_value.csv", rows(8, good) + "1,2,3,4,5,6,2\n" + rows(7, good),
       "truth_value.csv:9:", "must be 0 or 1"},
  };
  for (const Bad& bad : cases) {
    const auto path = write_text(bad.name, bad.text);
    const std::string message = read_error(path);
    EXPECT_NE(message.find(path.string() + bad.where.substr(bad.name.size())), std::string::npos)
        << bad.name << ": " << message;
    EXPECT_NE(message.find(bad.what), std::string::npos) << bad.name << ": " << message;
  }
  const std::string missing = read_error(temp_file("does_not_exist.csv"));
  EXPECT_NE(missing.find("does_not_exist.csv: cannot open"), std::string::npos) << missing;
}

TEST(CcdQueryFile, AcceptsBlankLinesAndWindowsLineEnds) {
  const auto path = write_text("crlf.csv", rows(8, "1,2,-3,4,5,6,1\r") + "\n\n");
  const std::vector<CcdQuery> queries = read_ccd_query_file(path, CcdQueryType::kVertexFace);
  ASSERT_EQ(queries.size(), 1u);
  EXPECT_TRUE(queries[0].collides);
  EXPECT_EQ(queries[0].vertices[7], Eigen::Vector3d(0.5, -0.75, 5.0 / 6.0));
}

}  // namespace
