#pragma once
// The dataset's columns: every HDF5 dataset of a dataset file, once, in creation order
// (docs/dataset-format.md). Adding a column is one entry in dataset_columns.cpp.
#include <cstddef>
#include <span>

#include "io/column.hpp"

namespace grip::io {

std::span<const Column> dataset_columns();

// What a checksum row covers: the columns each commit writes (stress, trajectory and result
// columns), one entry each, in table order.
bool checksummed(const Column& column);
std::size_t checksum_entries();
// The entry of a checksummed column (one of dataset_columns()) in a checksum row.
std::size_t checksum_entry(const Column& column);

}  // namespace grip::io
