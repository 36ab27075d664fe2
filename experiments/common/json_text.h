// The one way cmt turns JSON into text. Strings that come from the user (task and sweep files, paths, error
// messages quoting them) may hold bytes that are not UTF-8; nlohmann's default dump() throws on those, so
// every writer goes through here: invalid bytes become U+FFFD, and the text stays valid JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace cmt {

// indent < 0: compact; otherwise pretty with that many spaces.
inline std::string json_text(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

}  // namespace cmt
