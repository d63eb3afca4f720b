#pragma once
// Column accessors made from record members: field<&Record::member>() gets and puts one member
// (a number, enumeration or string, or an array, vector or optional vector of them), through a
// chain of members where it is nested (field<&A::b, &B::c>() is a.b.c).
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/column.hpp"

namespace grip::io::column_access {

// The index of std::vector<Value> among the Values alternatives.
template <typename Value, std::size_t kIndex = 0>
constexpr std::size_t values_holding() {
  if constexpr (std::is_same_v<std::variant_alternative_t<kIndex, Values>, std::vector<Value>>) {
    return kIndex;
  } else {
    return values_holding<Value, kIndex + 1>();
  }
}

// How one field's values go to and from a vector of Value.
template <typename Field>
struct FieldValues {  // one number, enumeration or string
  using Value = typename std::conditional_t<std::is_enum_v<Field>, std::underlying_type<Field>,
                                            std::type_identity<Field>>::type;
  static std::size_t size(const Field&) { return 1; }
  static void get(const Field& field, std::vector<Value>& out) {
    out.push_back(static_cast<Value>(field));
  }
  static void put(const std::vector<Value>& in, Field& field) {
    field = static_cast<Field>(in.at(0));
  }
};

template <typename T>
struct FieldValues<std::vector<T>> {
  using Value = typename FieldValues<T>::Value;
  static std::size_t size(const std::vector<T>& field) { return field.size(); }
  static void get(const std::vector<T>& field, std::vector<Value>& out) {
    if constexpr (std::is_same_v<T, Value>) {
      out.insert(out.end(), field.begin(), field.end());
    } else {
      for (const T& value : field) out.push_back(static_cast<Value>(value));
    }
  }
  static void put(const std::vector<Value>& in, std::vector<T>& field) {
    if constexpr (std::is_same_v<T, Value>) {
      field.assign(in.begin(), in.end());
    } else {
      field.clear();
      for (const Value& value : in) field.push_back(static_cast<T>(value));
    }
  }
};

template <typename T, std::size_t kSize>
struct FieldValues<std::array<T, kSize>> {
  using Value = typename FieldValues<T>::Value;
  static std::size_t size(const std::array<T, kSize>&) { return kSize; }
  static void get(const std::array<T, kSize>& field, std::vector<Value>& out) {
    for (const T& value : field) out.push_back(static_cast<Value>(value));
  }
  static void put(const std::vector<Value>& in, std::array<T, kSize>& field) {
    for (std::size_t i = 0; i < kSize; ++i) field[i] = static_cast<T>(in.at(i));
  }
};

template <typename T>
struct FieldValues<std::optional<T>> {  // get only where the field holds a value
  using Value = typename FieldValues<T>::Value;
  static std::size_t size(const std::optional<T>& field) {
    return field ? FieldValues<T>::size(*field) : 0;
  }
  static void get(const std::optional<T>& field, std::vector<Value>& out) {
    FieldValues<T>::get(field.value(), out);
  }
  static void put(const std::vector<Value>& in, std::optional<T>& field) {
    FieldValues<T>::put(in, field.emplace());
  }
};

template <typename Pointer>
struct MemberPointer;
template <typename Class, typename Member>
struct MemberPointer<Member Class::*> {
  using Record = Class;
};

// The member that a chain of member pointers reaches from a record.
template <auto kFirst, auto... kRest>
struct Chain {
  using Record = typename MemberPointer<decltype(kFirst)>::Record;
  template <typename R>
  static auto& of(R& record) {
    return ((record.*kFirst).*....*kRest);
  }
};

template <auto... kMembers>
constexpr auto field() {
  using Path = Chain<kMembers...>;
  using Record = typename Path::Record;
  using Field = std::remove_cvref_t<decltype(Path::of(std::declval<Record&>()))>;
  using Value = typename FieldValues<Field>::Value;
  return Access<Record>{
      values_holding<Value>(),
      [](const Record& record, Values& out) {
        FieldValues<Field>::get(Path::of(record), std::get<std::vector<Value>>(out));
      },
      [](const Values& in, Record& record) {
        FieldValues<Field>::put(std::get<std::vector<Value>>(in), Path::of(record));
      },
      [](const Record& record) { return FieldValues<Field>::size(Path::of(record)); }};
}

}  // namespace grip::io::column_access
