#pragma once
// canonical_bytes(value): every field of a plain struct, recursively, as bytes that two values share
// only when they are equal. The run pipeline hashes a stage's recipe with it (framework/pipeline/
// stage.hpp), so a field added to a recipe is in the stage's input hash without being listed anywhere
// else: a hand-written list of what to hash, which goes stale when the recipe grows, cannot exist
// (issue 30).
//
// Supported: bool, integers, floating point (bit for bit), enums (their underlying value), std::string,
// std::optional, std::vector, std::map, std::pair, std::array, and aggregates (plain structs without
// base classes, constructors or private members) of those with up to kMaxCanonicalFields fields.
// Strings and containers carry their length, and every value its type tag, so no two different
// sequences of values give the same bytes. A type outside this list does not compile.
//
// How the fields of an aggregate are found without naming them: the number of fields N is the largest
// N for which T{x1, ..., xN} compiles with values convertible to anything (no brace elision happens,
// since each converts to the member's type directly); structured bindings of exactly N names then
// reach them in declaration order (a wrong N would not compile).
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace crowdlab {

inline constexpr std::size_t kMaxCanonicalFields = 24;

namespace canonical_detail {

/// Converts to any type: only used unevaluated, to count an aggregate's fields.
struct AnyField {
  template <class T>
  operator T() const;  // NOLINT(google-explicit-constructor): the point is the implicit conversion
};

template <class T, std::size_t... I>
constexpr bool brace_initialisable(std::index_sequence<I...>) {
  return requires {
    T{(void(I), AnyField{})...};
  };
}

template <class T, std::size_t N = 0>
constexpr std::size_t field_count() {
  if constexpr (N < kMaxCanonicalFields && brace_initialisable<T>(std::make_index_sequence<N + 1>{}))
    return field_count<T, N + 1>();
  else
    return N;
}

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};
template <class T>
struct IsPair : std::false_type {};
template <class A, class B>
struct IsPair<std::pair<A, B>> : std::true_type {};
template <class T>
struct IsArray : std::false_type {};
template <class T, std::size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};
template <class T>
struct IsSequence : std::false_type {};
template <class T>
struct IsSequence<std::vector<T>> : std::true_type {};
template <class K, class V>
struct IsSequence<std::map<K, V>> : std::true_type {};

/// Calls f(fields...) on the fields of aggregate `v`, in declaration order.
template <class T, class F>
void for_fields(const T& v, F&& f) {
  constexpr std::size_t n = field_count<T>();
  static_assert(n < kMaxCanonicalFields, "canonical_bytes: too many fields (raise kMaxCanonicalFields)");
  // clang-format off
  if constexpr (n == 0) { (void)v; f(); }
  else if constexpr (n == 1) { const auto& [a] = v; f(a); }
  else if constexpr (n == 2) { const auto& [a, b] = v; f(a, b); }
  else if constexpr (n == 3) { const auto& [a, b, c] = v; f(a, b, c); }
  else if constexpr (n == 4) { const auto& [a, b, c, d] = v; f(a, b, c, d); }
  else if constexpr (n == 5) { const auto& [a, b, c, d, e] = v; f(a, b, c, d, e); }
  else if constexpr (n == 6) { const auto& [a, b, c, d, e, g] = v; f(a, b, c, d, e, g); }
  else if constexpr (n == 7) { const auto& [a, b, c, d, e, g, h] = v; f(a, b, c, d, e, g, h); }
  else if constexpr (n == 8) { const auto& [a, b, c, d, e, g, h, i] = v; f(a, b, c, d, e, g, h, i); }
  else if constexpr (n == 9) { const auto& [a, b, c, d, e, g, h, i, j] = v; f(a, b, c, d, e, g, h, i, j); }
  else if constexpr (n == 10) { const auto& [a, b, c, d, e, g, h, i, j, k] = v; f(a, b, c, d, e, g, h, i, j, k); }
  else if constexpr (n == 11) { const auto& [a, b, c, d, e, g, h, i, j, k, l] = v; f(a, b, c, d, e, g, h, i, j, k, l); }
  else if constexpr (n == 12) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m] = v; f(a, b, c, d, e, g, h, i, j, k, l, m); }
  else if constexpr (n == 13) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o); }
  else if constexpr (n == 14) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p); }
  else if constexpr (n == 15) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q); }
  else if constexpr (n == 16) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r); }
  else if constexpr (n == 17) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s); }
  else if constexpr (n == 18) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t); }
  else if constexpr (n == 19) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u); }
  else if constexpr (n == 20) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w); }
  else if constexpr (n == 21) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w, x] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w, x); }
  else if constexpr (n == 22) { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w, x, y] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w, x, y); }
  else { const auto& [a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w, x, y, z] = v; f(a, b, c, d, e, g, h, i, j, k, l, m, o, p, q, r, s, t, u, w, x, y, z); }
  // clang-format on
}

template <class T>
void append_raw(std::string& out, const T& v) {
  const auto bytes = std::bit_cast<std::array<char, sizeof(T)>>(v);
  out.append(bytes.data(), bytes.size());
}

template <class T>
void append(std::string& out, const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    out += v ? "b1" : "b0";
  } else if constexpr (std::is_enum_v<T>) {
    out += 'e';
    append_raw(out, static_cast<std::int64_t>(v));
  } else if constexpr (std::is_integral_v<T>) {
    out += std::is_signed_v<T> ? 'i' : 'u';
    append_raw(out, static_cast<std::conditional_t<std::is_signed_v<T>, std::int64_t, std::uint64_t>>(v));
  } else if constexpr (std::is_floating_point_v<T>) {
    out += 'f';
    append_raw(out, static_cast<double>(v));
  } else if constexpr (std::is_same_v<T, std::string>) {
    out += 's';
    append_raw(out, static_cast<std::uint64_t>(v.size()));
    out += v;
  } else if constexpr (IsOptional<T>::value) {
    out += v ? '+' : '-';
    if (v) append(out, *v);
  } else if constexpr (IsPair<T>::value) {
    append(out, v.first);
    append(out, v.second);
  } else if constexpr (IsArray<T>::value || IsSequence<T>::value) {
    out += '[';
    append_raw(out, static_cast<std::uint64_t>(v.size()));
    for (const auto& item : v) append(out, item);
    out += ']';
  } else {
    static_assert(std::is_aggregate_v<T>, "canonical_bytes: unsupported field type");
    out += '{';
    for_fields(v, [&out](const auto&... fields) { (append(out, fields), ...); });
    out += '}';
  }
}

}  // namespace canonical_detail

/// The canonical bytes of `value` (see above): equal values give equal bytes, and values that differ in
/// any field, however deep, give different bytes.
template <class T>
std::string canonical_bytes(const T& value) {
  std::string out;
  canonical_detail::append(out, value);
  return out;
}

/// The number of fields canonical_bytes() sees in aggregate T (for tests of a recipe's coverage).
template <class T>
constexpr std::size_t canonical_field_count() {
  return canonical_detail::field_count<T>();
}

}  // namespace crowdlab
