#include "io/column_values.hpp"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

namespace grip::io {

namespace {

template <std::size_t... kIndex>
Values empty_values_of(std::size_t index, std::index_sequence<kIndex...>) {
  Values values;
  ((index == kIndex ? (values.emplace<kIndex>(), 0) : 0), ...);
  return values;
}

template <typename Vector>
using ValueOf = typename std::remove_cvref_t<Vector>::value_type;

}  // namespace

Values empty_values(std::size_t index) {
  if (index >= std::variant_size_v<Values>) throw std::out_of_range("no such value type");
  return empty_values_of(index, std::make_index_sequence<std::variant_size_v<Values>>());
}

std::size_t value_count(const Values& values) {
  return std::visit([](const auto& v) { return v.size(); }, values);
}

Values slice(const Values& values, std::size_t offset, std::size_t count) {
  return std::visit(
      [&](const auto& v) -> Values {
        const auto begin = v.begin() + static_cast<std::ptrdiff_t>(offset);
        return std::remove_cvref_t<decltype(v)>(begin, begin + static_cast<std::ptrdiff_t>(count));
      },
      values);
}

void append(Values& out, const Values& values) {
  std::visit(
      [&](auto& o) {
        const auto& v = std::get<std::remove_cvref_t<decltype(o)>>(values);
        o.insert(o.end(), v.begin(), v.end());
      },
      out);
}

void append_padded(Values& out, const Values& values, std::uint32_t hands, std::size_t per_hand,
                   std::uint32_t max_hands, std::size_t width, double pad) {
  std::visit(
      [&](auto& o) {
        using T = ValueOf<decltype(o)>;
        if constexpr (std::is_arithmetic_v<T>) {
          const auto& v = std::get<std::vector<T>>(values);
          const T padding = static_cast<T>(pad);
          for (std::uint32_t h = 0; h < max_hands; ++h) {
            if (h < hands) {
              const auto begin = v.begin() + static_cast<std::ptrdiff_t>(h * per_hand);
              o.insert(o.end(), begin, begin + static_cast<std::ptrdiff_t>(per_hand));
              o.insert(o.end(), width - per_hand, padding);
            } else {
              o.insert(o.end(), width, padding);
            }
          }
        } else {
          throw std::logic_error("strings are not padded per hand");
        }
      },
      out);
}

Values unpadded(const Values& row, std::uint32_t hands, std::size_t per_hand, std::size_t width) {
  return std::visit(
      [&](const auto& v) -> Values {
        std::remove_cvref_t<decltype(v)> values;
        for (std::uint32_t h = 0; h < hands; ++h) {
          const auto begin = v.begin() + static_cast<std::ptrdiff_t>(h * width);
          values.insert(values.end(), begin, begin + static_cast<std::ptrdiff_t>(per_hand));
        }
        return values;
      },
      row);
}

std::size_t string_width(const std::vector<std::string>& strings) {
  std::size_t width = 1;
  for (const auto& value : strings) width = std::max(width, value.size());
  return width;
}

std::vector<char> packed_strings(const std::vector<std::string>& strings, std::size_t width) {
  std::vector<char> packed(strings.size() * width, '\0');
  for (std::size_t i = 0; i < strings.size(); ++i) {
    std::copy(strings[i].begin(), strings[i].end(), packed.begin() + i * width);
  }
  return packed;
}

namespace {

template <typename Pointer, typename Vector>
Pointer data_of(Vector& v) {
  if constexpr (std::is_arithmetic_v<ValueOf<Vector>>) {
    return v.data();
  } else {
    throw std::logic_error("strings are packed, not handed over as numbers");
  }
}

}  // namespace

const void* number_data(const Values& values) {
  return std::visit([](const auto& v) { return data_of<const void*>(v); }, values);
}

void* number_data(Values& values) {
  return std::visit([](auto& v) { return data_of<void*>(v); }, values);
}

}  // namespace grip::io
