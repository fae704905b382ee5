// SPDX-License-Identifier: BSD-3-Clause
// Names of small enums from a table indexed by the enumerator's value,
// shared by the scene headers (scenes.h, query_scenes.h).
#pragma once

#include <cstddef>

namespace tricyl::enum_names {

/// names[e] for an enum whose enumerators are 0, 1, ..., N - 1 (the
/// default numbering, names in declaration order); "?" for any other value.
template <class E, std::size_t N>
constexpr const char* nameOf(E e, const char* const (&names)[N]) {
  const auto i = static_cast<std::size_t>(e);
  return i < N ? names[i] : "?";
}

}  // namespace tricyl::enum_names
