#pragma once
// The dataset's columns: every HDF5 dataset of a dataset file, once, in creation order (format
// version 1, docs/dataset-format.md). Adding a column is one entry in dataset_columns.cpp.
#include <span>

#include "io/column.hpp"

namespace grip::io {

std::span<const Column> dataset_columns();

}  // namespace grip::io
