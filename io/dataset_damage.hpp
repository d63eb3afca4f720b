#pragma once
// Finds committed rows whose stored bytes no longer match the checksums their commit round
// wrote beside them (docs/dataset-format.md, "Checksums"): what resume redoes and what
// `grip inspect` reports instead of counting it done.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

#include "io/dataset_layout.hpp"

namespace grip::io {

struct Damage {
  std::uint64_t candidate = 0;
  std::string dataset;  // the column whose row does not match, e.g. "/candidates/d1"
};

// Checks every candidate where `check` is 1: its row of each result column, and its trajectory
// and stress rows where its written flags say it has them. Reads the data in blocks of a few
// MB. In candidate order, then the column table's order.
std::vector<Damage> find_damage(hid_t file, const DatasetLayout& layout,
                                const std::vector<std::uint8_t>& check);

}  // namespace grip::io
