// Text helpers for the self-contained HTML and SVG reports (quality, batch summary, evaluation).
#pragma once

#include <string>
#include <vector>

namespace bcot {

// `text` with & < > " ' escaped, safe in HTML/SVG element content and quoted attributes.
std::string HtmlEscape(const std::string& text);

// `bytes` in standard Base64 (RFC 4648, with padding), for data: URIs of inline images.
std::string Base64(const std::vector<unsigned char>& bytes);

}  // namespace bcot
