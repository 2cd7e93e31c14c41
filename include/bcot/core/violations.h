// Joins option violations into one kInvalidConfig status ("context: a; b; c"), for the
// Validate() of option structs.
#pragma once

#include <string>
#include <vector>

#include "bcot/core/status.h"

namespace bcot::internal {

inline Status JoinViolations(const std::string& context,
                             const std::vector<std::string>& violations) {
  if (violations.empty()) return Status::Ok();
  std::string message = context + ": " + violations[0];
  for (size_t i = 1; i < violations.size(); ++i) message += "; " + violations[i];
  return Status::InvalidConfig(message);
}

}  // namespace bcot::internal
