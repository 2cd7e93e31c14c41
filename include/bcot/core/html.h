// Text helpers for the self-contained HTML and SVG reports (quality, batch summary, evaluation).
#pragma once

#include <string>

namespace bcot {

// `text` with & < > " ' escaped, safe in HTML/SVG element content and quoted attributes.
std::string HtmlEscape(const std::string& text);

}  // namespace bcot
