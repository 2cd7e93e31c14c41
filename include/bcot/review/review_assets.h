// The static files of `bcot review`'s page (index.html, review.js, review.css from
// src/review/web/), compiled into the binary by cmake/embed_review_assets.cmake.
#pragma once

#include <string_view>
#include <vector>

namespace bcot {

struct ReviewAsset {
  std::string_view name;     // file name, e.g. "review.js"
  std::string_view content;  // the file's bytes
};

// Every asset; immutable, built on first use (thread-safe).
const std::vector<ReviewAsset>& ReviewAssets();

// The asset called exactly `name`, or nullptr.
const ReviewAsset* FindReviewAsset(std::string_view name);

// The Content-Type of an asset by its extension (text/html, text/javascript, text/css;
// application/octet-stream otherwise).
const char* ReviewAssetContentType(std::string_view name);

}  // namespace bcot
