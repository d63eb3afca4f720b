#pragma once
// What one column (HDF5 dataset) of a dataset file is: where it lives, its element type, the
// extents of one record's part, its fill value and how its values come out of a record and go
// back in. The table of every column is dataset_columns(); writer and reader loop over it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "io/candidate_record.hpp"
#include "io/column_values.hpp"
#include "io/dataset_layout.hpp"
#include "io/gripper_record.hpp"
#include "io/hdf5.hpp"
#include "io/object_record.hpp"
#include "io/provenance.hpp"

namespace grip::io {

// Where a column lives, which record fills it, and when it is written. Provenance, object and
// gripper columns hold one record's values whole; the others one row per slot.
enum class Place : std::uint8_t {
  kProvenance,    // /provenance/NAME: the whole dataset from the Provenance, at creation
  kObject,        // /objects/OOOOOO/NAME: the whole dataset from the ObjectRecord, at creation
  kStress,        // /objects/OOOOOO/NAME: one row per stress slot, from a CandidateResult
  kTrajectory,    // /objects/OOOOOO/trajectories/GGG/NAME: one row per frame slot
  kGripper,       // /grippers/GGG/NAME: the whole dataset from the GripperRecord, at creation
  kFingerStress,  // /grippers/GGG/NAME: one row per finger stress slot, from a CandidateResult
  kPlan,          // /candidates/NAME: one row per candidate, from the DatasetLayout, at creation
  kResult,        // /candidates/NAME: one row per candidate, from its CandidateResult, per batch
  kDone,          // /candidates/NAME: one row per candidate, set once its batch is committed
  kChecksum,      // /candidates/NAME: one row per candidate, its rows' checksums, per batch
};

// Element types. Files store them little-endian; status and failure are HDF5 enumerations.
enum class Element : std::uint8_t {
  kFloat64,
  kFloat32,
  kInt32,
  kInt64,
  kUint32,
  kUint8,
  kStatus,
  kFailureKind,
  kString,  // fixed-length, NUL-padded, as wide as the longest value (at least 1)
};

// The HDF5 type of an element in the file or in memory (`width`: string length).
h5::Handle element_type(Element element, bool file, std::size_t width = 1);

// The Values alternative that holds an element in memory.
constexpr std::size_t value_index(Element element) {
  switch (element) {
    case Element::kFloat64:
      return 0;
    case Element::kFloat32:
      return 1;
    case Element::kInt32:
      return 2;
    case Element::kInt64:
      return 3;
    case Element::kUint32:
      return 4;
    case Element::kUint8:
    case Element::kStatus:
    case Element::kFailureKind:
      return 5;
    case Element::kString:
      return 6;
  }
  return 0;
}

enum class Fill : std::uint8_t {
  kUnset,  // HDF5's default fill properties (the string datasets, written whole at creation)
  kNever,  // no fill: space as allocated, read only where a record was written
  kZero,   // zero (and `pending` for a status) until a record is written
  kNaN,    // NaN until a record is written; also pads rows narrower than the table
};

// Fill as bytes of the element's memory type (kZero, kNaN).
std::array<std::byte, 8> fill_bytes(Element element, Fill fill);

using Dims = std::vector<hsize_t>;

// What the extents of a column's part of one record may depend on.
struct Sizes {
  std::uint64_t frames = 0;  // closing + validation frames
  std::uint32_t max_hands = 1;
  std::uint32_t max_joints = 1;
  std::uint32_t max_fingers = 1;
  DatasetLayout::Object object;    // the row's object
  DatasetLayout::Gripper gripper;  // the row's gripper
  std::uint64_t count = 0;         // values a whole-record column holds

  // The table's sizes (frames and widths), then those of a row of `object` and `gripper`.
  static Sizes of(const DatasetLayout& layout);
  static Sizes of(const DatasetLayout& layout, std::uint32_t object, std::uint32_t gripper);
  // The sizes of candidate `id`'s rows.
  static Sizes of_candidate(const DatasetLayout& layout, std::uint64_t id);
};

// How a column's values come out of a Record and go back in, in the memory type of its
// element (the Values alternative `value_index`).
template <typename Record>
struct Access {
  std::size_t value_index = 0;
  void (*get)(const Record&, Values&) = nullptr;  // appends the record's values
  void (*put)(const Values&, Record&) = nullptr;  // null: not read back into the record
  std::size_t (*size)(const Record&) = nullptr;   // values the record holds
};

struct Column {
  const char* name;
  Place place;
  Element element;
  Fill fill;
  // The extents of one row, or of the whole dataset for a column that holds a record whole.
  Dims (*extents)(const Sizes&);
  // Per place: Provenance, ObjectRecord, CandidateResult (stress), TrajectoryRecord,
  // GripperRecord, CandidateResult (finger stress), DatasetLayout, CandidateResult, none (done,
  // checksum).
  std::variant<std::monostate, Access<Provenance>, Access<ObjectRecord>, Access<GripperRecord>,
               Access<TrajectoryRecord>, Access<DatasetLayout>, Access<CandidateResult>>
      access;
  // Set for a column of hands: a record holds `per_hand` values for each hand of its gripper,
  // a row holds max_hands blocks as wide as the table's (extents), padded with the fill.
  std::uint32_t (*per_hand)(const DatasetLayout::Gripper&) = nullptr;

  template <typename Record>
  const Access<Record>& access_to() const {
    return std::get<Access<Record>>(access);
  }
};

// A whole dataset's values, and row `row` of a dataset whose first dimension indexes rows
// (`path` names it in errors), in the memory type of `element`.
Values read_values(hid_t dataset, Element element);
Values read_row_values(hid_t dataset, const std::string& path, std::uint64_t row, Element element);
// Rows [first, first + rows) of such a dataset; DatasetError if it has not that many.
Values read_rows_values(hid_t dataset, const std::string& path, std::uint64_t first,
                        std::uint64_t rows, Element element);

// Bytes of one number of `element` in memory (0 for strings).
std::size_t element_bytes(Element element);

// Values in one row of a row place's column.
std::size_t row_size(const Column& column, const Sizes& sizes);
// Values a record must hold for a row: the row's, or its gripper's hands x per_hand.
std::size_t record_size(const Column& column, const Sizes& sizes);

}  // namespace grip::io
