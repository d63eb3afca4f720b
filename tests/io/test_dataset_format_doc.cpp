// docs/dataset-format.md names exactly the columns of io/dataset_columns.cpp and lists the
// checksummed ones in order, and examples/read_dataset.py reads only columns the table has.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/dataset_columns.hpp"

namespace grip::io {
namespace {

const std::string kSourceDir = GRIP_SOURCE_DIR;

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The group a place's columns are documented under, as the page's section headings name it
// (trajectories are rows `trajectories/GGG/NAME` of the object's table).
std::string documented_group(Place place) {
  switch (place) {
    case Place::kProvenance:
      return "/provenance";
    case Place::kObject:
    case Place::kStress:
      return "/objects/OOOOOO";
    case Place::kTrajectory:
      return "/objects/OOOOOO/trajectories/GGG";
    case Place::kGripper:
    case Place::kFingerStress:
      return "/grippers/GGG";
    case Place::kPlan:
    case Place::kResult:
    case Place::kDone:
    case Place::kChecksum:
      return "/candidates";
  }
  return "";
}

std::set<std::string> table_paths() {
  std::set<std::string> paths;
  for (const Column& column : dataset_columns()) {
    paths.insert(documented_group(column.place) + "/" + column.name);
  }
  return paths;
}

// The `backticked` spans of a line, in order.
std::vector<std::string> code_spans(const std::string& line) {
  std::vector<std::string> spans;
  for (std::size_t open = line.find('`'); open != std::string::npos;) {
    const std::size_t close = line.find('`', open + 1);
    if (close == std::string::npos) break;
    spans.push_back(line.substr(open + 1, close - open - 1));
    open = line.find('`', close + 1);
  }
  return spans;
}

std::string trimmed(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
}

struct Named {
  std::string path;
  int line = 0;
};

// The datasets the page's column tables name. A column table is a table whose header's first
// cell is "dataset" or "column"; each row's first cell names one or more datasets in
// backticks, relative to the group its section heading names in its first backticked span
// (### `/candidates`: ...). Fenced code blocks are skipped.
std::vector<Named> documented_columns(const std::string& page) {
  std::vector<Named> named;
  std::istringstream lines(page);
  std::string line;
  std::string group;
  bool fenced = false;
  bool in_table = false;
  bool column_table = false;
  int table_row = 0;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (line.starts_with("```")) fenced = !fenced;
    if (fenced) continue;
    if (line.starts_with("#")) {
      const std::vector<std::string> spans = code_spans(line);
      group = !spans.empty() && spans[0].starts_with("/") ? spans[0] : "";
    }
    if (!line.starts_with("|")) {
      in_table = false;
      continue;
    }
    const std::string first = trimmed(line.substr(1, line.find('|', 1) - 1));
    if (!in_table) {  // the header
      in_table = true;
      column_table = first == "dataset" || first == "column";
      table_row = 0;
      continue;
    }
    if (++table_row == 1 || !column_table) continue;  // the | --- | line, or another table
    const std::vector<std::string> spans = code_spans(first);
    EXPECT_FALSE(spans.empty()) << "docs/dataset-format.md:" << number
                                << ": a column table's row names no dataset in backticks";
    EXPECT_FALSE(group.empty()) << "docs/dataset-format.md:" << number
                                << ": a column table under a heading that names no group";
    for (const std::string& name : spans) named.push_back({group + "/" + name, number});
  }
  return named;
}

TEST(DatasetFormatDoc, NamesEveryColumnOfTheTableAndNoOther) {
  const std::vector<Named> named =
      documented_columns(text_of(kSourceDir + "/docs/dataset-format.md"));
  const std::set<std::string> table = table_paths();
  std::map<std::string, int> documented;
  for (const Named& name : named) {
    EXPECT_TRUE(table.count(name.path) == 1)
        << "docs/dataset-format.md:" << name.line << " names " << name.path
        << ", which is not a column of io/dataset_columns.cpp";
    const auto [where, first] = documented.emplace(name.path, name.line);
    EXPECT_TRUE(first) << "docs/dataset-format.md:" << name.line << " names " << name.path
                       << " again (first on line " << where->second << ")";
  }
  for (const std::string& path : table) {
    EXPECT_TRUE(documented.count(path) == 1)
        << "column " << path << " of io/dataset_columns.cpp is missing from a column table of "
        << "docs/dataset-format.md";
  }
}

// The "Checksum entries, in order:" sentence names the checksummed columns in the order of the
// entries of a checksum row.
TEST(DatasetFormatDoc, ListsTheChecksumEntriesInOrder) {
  const std::string page = text_of(kSourceDir + "/docs/dataset-format.md");
  const std::string marker = "Checksum entries, in order:";
  const std::size_t start = page.find(marker);
  ASSERT_NE(start, std::string::npos) << "docs/dataset-format.md has no '" << marker << "'";
  std::vector<std::string> listed;
  bool quoted = false;
  std::string name;
  for (std::size_t i = start + marker.size(); i < page.size(); ++i) {
    const char c = page[i];
    if (c == '`') {
      if (quoted) listed.push_back(name);
      name.clear();
      quoted = !quoted;
    } else if (quoted) {
      name += c;
    } else if (c == '.') {
      break;
    }
  }
  std::vector<std::string> entries;
  for (const Column& column : dataset_columns()) {
    if (checksummed(column)) entries.push_back(column.name);
  }
  EXPECT_EQ(entries.size(), checksum_entries());
  EXPECT_EQ(listed, entries);
}

// The example reads candidate columns as table["NAME"] and trajectory columns as
// frames["NAME"].
TEST(DatasetFormatDoc, ExampleReadsOnlyColumnsOfTheTable) {
  const std::string example = text_of(kSourceDir + "/examples/read_dataset.py");
  const std::set<std::string> table = table_paths();
  const std::map<std::string, std::string> groups = {
      {"table", documented_group(Place::kResult)},
      {"frames", documented_group(Place::kTrajectory)}};
  const std::regex read(R"((table|frames)\[["'](\w+)["']\])");
  int reads = 0;
  for (auto match = std::sregex_iterator(example.begin(), example.end(), read);
       match != std::sregex_iterator(); ++match, ++reads) {
    const std::string path = groups.at((*match)[1]) + "/" + (*match)[2].str();
    EXPECT_TRUE(table.count(path) == 1)
        << "examples/read_dataset.py reads " << path << ", which is not a column";
  }
  EXPECT_GT(reads, 0) << "examples/read_dataset.py reads no column as table[...] or frames[...]";
}

}  // namespace
}  // namespace grip::io
