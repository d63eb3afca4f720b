#pragma once
// One column's values in memory, in the native type of its element: what a record's accessor
// appends to and reads from, and what the writer and reader hand to HDF5.
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace grip::io {

using Values = std::variant<std::vector<double>, std::vector<float>, std::vector<std::int32_t>,
                            std::vector<std::int64_t>, std::vector<std::uint32_t>,
                            std::vector<std::uint8_t>, std::vector<std::string>>;

// An empty Values of alternative `index`.
Values empty_values(std::size_t index);

std::size_t value_count(const Values& values);

// Values [offset, offset + count) of `values`.
Values slice(const Values& values, std::size_t offset, std::size_t count);

// Appends `values` to `out` (the same alternative).
void append(Values& out, const Values& values);

// Appends `hands` blocks of `per_hand` values as `max_hands` blocks of `width`, padding with
// `pad` (numbers only): a row of a table column sized for the largest gripper.
void append_padded(Values& out, const Values& values, std::uint32_t hands, std::size_t per_hand,
                   std::uint32_t max_hands, std::size_t width, double pad);

// The first `hands` blocks of a row of `width`-wide blocks, each cut to `per_hand` values.
Values unpadded(const Values& row, std::uint32_t hands, std::size_t per_hand, std::size_t width);

// The longest string's length (at least 1), and the strings NUL-padded to that width.
std::size_t string_width(const std::vector<std::string>& strings);
std::vector<char> packed_strings(const std::vector<std::string>& strings, std::size_t width);

// The numbers' first byte (not for strings).
const void* number_data(const Values& values);
void* number_data(Values& values);

}  // namespace grip::io
