// Range checks of input values (a flag, an option field, a scene parameter). Each throws
// InputError (core/error.h) with one line in the same form, "NAME: must be …", so every
// option's range reads alike and each check is one line. Real numbers outside, or NaN, fail.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>

#include "proxima/core/error.h"

namespace proxima {

namespace detail {
// Throws InputError "NAME: must be REQUIREMENT", then " NOTE" when `note` is not empty.
[[noreturn]] void fail_requirement(std::string_view name, const std::string& requirement, std::string_view note);
// A bound as the messages print it: integers in full, real numbers with up to 6 significant
// digits ("0.01", "100").
std::string bound_text(long long bound);
std::string bound_text(double bound);
}  // namespace detail

// lo ≤ value ≤ hi, else "NAME: must be in LO..HI" (integers) or "NAME: must be in [LO, HI]"
// (real numbers), followed by " NOTE" when given (a unit, what 0 means, a condition).
template <typename T>
  requires std::is_arithmetic_v<T>
void require_in_range(T value, std::type_identity_t<T> lo, std::type_identity_t<T> hi, std::string_view name,
                      std::string_view note = {}) {
  if (value >= lo && value <= hi) return;
  if constexpr (std::is_integral_v<T>)
    detail::fail_requirement(name, "in " + detail::bound_text((long long)lo) + ".." + detail::bound_text((long long)hi),
                             note);
  else
    detail::fail_requirement(name, "in [" + detail::bound_text(double(lo)) + ", " + detail::bound_text(double(hi)) + "]",
                             note);
}

// lo < value ≤ hi, else "NAME: must be in (LO, HI]" (then " NOTE").
template <typename T>
  requires std::is_floating_point_v<T>
void require_above_at_most(T value, std::type_identity_t<T> lo, std::type_identity_t<T> hi, std::string_view name,
                           std::string_view note = {}) {
  if (value > lo && value <= hi) return;
  detail::fail_requirement(name, "in (" + detail::bound_text(double(lo)) + ", " + detail::bound_text(double(hi)) + "]",
                           note);
}

// value ≥ lo, else "NAME: must be ≥ LO" (then " NOTE"). Infinity passes, NaN fails.
template <typename T>
  requires std::is_arithmetic_v<T>
void require_at_least(T value, std::type_identity_t<T> lo, std::string_view name, std::string_view note = {}) {
  if (value >= lo) return;
  if constexpr (std::is_integral_v<T>)
    detail::fail_requirement(name, "≥ " + detail::bound_text((long long)lo), note);
  else
    detail::fail_requirement(name, "≥ " + detail::bound_text(double(lo)), note);
}

}  // namespace proxima
