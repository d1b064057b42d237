#pragma once
// The .msg files compiled in (msg_texts.cpp, generated).

#include <string_view>
#include <vector>

namespace swa::msg_defs::detail {

struct MsgText {
  std::string_view name;  // "Imu"
  std::string_view text;  // the file's content
};

// Sorted by name (the glob's order).
const std::vector<MsgText>& msgTexts();

}  // namespace swa::msg_defs::detail
