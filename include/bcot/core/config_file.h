// Messages joined into one status text. (Config files are read through OptionSchema,
// bcot/core/option_schema.h.)
#pragma once

#include <string>
#include <vector>

namespace bcot {

// Messages joined by "; ".
inline std::string JoinMessages(const std::vector<std::string>& messages) {
  std::string joined;
  for (const std::string& m : messages) joined += (joined.empty() ? "" : "; ") + m;
  return joined;
}

}  // namespace bcot
