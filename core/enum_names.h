// The names of an enum's values, table-driven: one constexpr list of {value, "name"} pairs gives
// ToString, FromString (an InputError that lists the valid names) and the names for help texts.
// Declared beside the enum, with the one-line hook that ToString and FromString find it by:
//
//   inline constexpr auto kLossNames = MakeEnumNames<LossKind>(
//       "loss", {{LossKind::kLog, "log"}, {LossKind::kL2, "l2"}});
//   constexpr const auto& EnumNamesOf(LossKind) { return kLossNames; }
//
//   ToString(LossKind::kL2);          // "l2"
//   FromString<LossKind>("cubic");    // InputError "unknown loss 'cubic' (expected log | l2)"
//   kLossNames.List();                // "log | l2"
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/error.h"

namespace brdfit {

template <class E>
struct EnumName {
  E value;
  const char* name;
  bool alias = false;  // also accepted by FromString, never printed (e.g. "binary" for "merl")
};

template <class E, std::size_t N>
class EnumNames {
 public:
  constexpr EnumNames(const char* what, const std::array<EnumName<E>, N>& names)
      : what_(what), names_(names) {}

  // The value's first name that is not an alias ("?" for a value the table lacks).
  constexpr const char* ToString(E e) const {
    for (const EnumName<E>& n : names_) {
      if (n.value == e && !n.alias) return n.name;
    }
    return "?";
  }

  constexpr std::optional<E> Find(std::string_view s) const {
    for (const EnumName<E>& n : names_) {
      if (s == n.name) return n.value;
    }
    return std::nullopt;
  }

  E FromString(const std::string& s) const {
    if (const std::optional<E> e = Find(s)) return *e;
    throw InputError(Unknown(s));
  }

  // "unknown <what> 's' (expected a | b | c)".
  std::string Unknown(std::string_view s) const {
    return "unknown " + std::string(what_) + " '" + std::string(s) + "' (expected " + List() + ")";
  }

  // The printed names, in table order: "a | b | c".
  std::string List(std::string_view separator = " | ") const {
    std::string out;
    for (const EnumName<E>& n : names_) {
      if (n.alias) continue;
      if (!out.empty()) out += separator;
      out += n.name;
    }
    return out;
  }

 private:
  const char* what_;
  std::array<EnumName<E>, N> names_;
};

template <class E, std::size_t N>
constexpr EnumNames<E, N> MakeEnumNames(const char* what, const EnumName<E> (&names)[N]) {
  return EnumNames<E, N>(what, std::to_array(names));
}

// An enum with a table: EnumNamesOf(E) is declared in E's namespace (argument-dependent lookup).
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) {
  EnumNamesOf(e).ToString(e);
};

template <NamedEnum E>
const char* ToString(E e) {
  return EnumNamesOf(e).ToString(e);
}

template <NamedEnum E>
E FromString(const std::string& s) {  // throws InputError
  return EnumNamesOf(E{}).FromString(s);
}

}  // namespace brdfit
