#pragma once
// Writes a new dataset's whole layout at creation (docs/dataset-format.md): the provenance, the
// objects, grippers and their trajectory groups, and the candidate table, every dataset made
// contiguous with its space allocated now, so that later commits write raw data only.
#include <hdf5.h>

#include <string>

#include "io/dataset_layout.hpp"
#include "io/dataset_plan.hpp"
#include "io/provenance.hpp"

namespace grip::io {

// Collective: every rank passes the same arguments; rank 0 writes the values known now (plan,
// records, provenance), the result columns start as their fill ("not written").
void write_layout(hid_t file, const DatasetPlan& plan, const DatasetLayout& layout,
                  const Provenance& provenance, int rank);

// Throws DatasetError when `file` (named `name` in messages) holds other objects, grippers or
// candidate slots than write_layout would write for `plan`: compared by the checksums written
// with them at creation. A resumed run's plan must be the one the dataset was made with, or
// its new rows would describe other meshes than the stored ones. Reads only.
void check_layout(hid_t file, const std::string& name, const DatasetPlan& plan,
                  const DatasetLayout& layout);

}  // namespace grip::io
