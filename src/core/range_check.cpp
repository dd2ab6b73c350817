#include "proxima/core/range_check.h"

#include <cstdio>

namespace proxima::detail {

void fail_requirement(std::string_view name, const std::string& requirement, std::string_view note) {
  std::string message(name);
  message += ": must be " + requirement;
  if (!note.empty()) (message += ' ') += note;
  fail_input(message);
}

std::string bound_text(long long bound) { return std::to_string(bound); }

std::string bound_text(double bound) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", bound);
  return text;
}

}  // namespace proxima::detail
