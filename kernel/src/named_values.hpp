#pragma once
// Tables of an enumeration's values with their names (and whatever else each value carries),
// one row a value in the enumeration's order: one table serves the names, their parsing and
// the rest, where a switch per use would list the values again each time.

#include <cstddef>
#include <optional>
#include <string_view>

namespace plyfit::detail {

/// A value and its name.
template <typename E>
struct Named {
  E value;
  const char* name;
};

/// True when the rows hold the values 0, 1, ..., `last` in order, each once: the table follows
/// its enumeration, whose last value `last` is (checked by a static_assert next to each table,
/// so that a value inserted in the enumeration breaks the build until the table has it; one
/// appended after `last` must be named there too).
template <typename Row, std::size_t N, typename E>
constexpr bool lists_enum(const Row (&table)[N], E last) {
  if (N != static_cast<std::size_t>(last) + 1) return false;
  for (std::size_t k = 0; k < N; ++k)
    if (static_cast<std::size_t>(table[k].value) != k) return false;
  return true;
}

/// The row of `value`, or nullptr for a value outside the table.
template <typename Row, std::size_t N, typename E>
constexpr const Row* row_of(const Row (&table)[N], E value) {
  const auto k = static_cast<std::size_t>(value);
  return k < N ? &table[k] : nullptr;
}

/// The name of `value`, or `fallback` for a value outside the table.
template <typename Row, std::size_t N, typename E>
constexpr const char* name_in(const Row (&table)[N], E value, const char* fallback) {
  const Row* row = row_of(table, value);
  return row ? row->name : fallback;
}

/// The value named `name`, if one is.
template <typename Row, std::size_t N>
auto value_named(const Row (&table)[N], std::string_view name)
    -> std::optional<decltype(table[0].value)> {
  for (const Row& row : table)
    if (name == row.name) return row.value;
  return std::nullopt;
}

}  // namespace plyfit::detail
