// Escaping text for HTML and SVG (the report page and its inline charts).
#pragma once

#include <string>

namespace proxima {

// `text` with & < > " replaced by their character references.
std::string html_escape(const std::string& text);

}  // namespace proxima
