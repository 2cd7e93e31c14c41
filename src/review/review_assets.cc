#include "bcot/review/review_assets.h"

namespace bcot {
namespace {

bool EndsWith(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

}  // namespace

const ReviewAsset* FindReviewAsset(std::string_view name) {
  for (const ReviewAsset& asset : ReviewAssets()) {
    if (asset.name == name) return &asset;
  }
  return nullptr;
}

const char* ReviewAssetContentType(std::string_view name) {
  if (EndsWith(name, ".html")) return "text/html; charset=utf-8";
  if (EndsWith(name, ".js")) return "text/javascript; charset=utf-8";
  if (EndsWith(name, ".css")) return "text/css; charset=utf-8";
  return "application/octet-stream";
}

}  // namespace bcot
