#include "json_value.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "swa/monitor/report.h"

namespace swa::monitor_node {

// Recursive descent over the text; depth-limited so a hostile file cannot overflow the stack.
class JsonParser {
 public:
  explicit JsonParser(std::string_view text) : text_(text) {}

  JsonValue document() {
    JsonValue v = value(0);
    skipSpace();
    if (pos_ != text_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  static constexpr int kMaxDepth = 64;

  [[noreturn]] void fail(const std::string& what) const {
    int line = 1;
    int column = 1;
    for (std::size_t k = 0; k < pos_ && k < text_.size(); ++k) {
      if (text_[k] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw JsonError("line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what);
  }

  void skipSpace() {
    while (pos_ < text_.size() &&
           (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\n' || text_[pos_] == '\r')) {
      ++pos_;
    }
  }

  bool consume(char c) {
    skipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  void expect(char c) {
    if (!consume(c)) fail(std::string("expected '") + c + "'");
  }

  bool literal(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  JsonValue value(int depth) {
    if (depth > kMaxDepth) fail("nested too deeply");
    skipSpace();
    if (pos_ >= text_.size()) fail("unexpected end of text");
    const char c = text_[pos_];
    if (c == '{') return object(depth);
    if (c == '[') return array(depth);
    if (c == '"') return JsonValue::string(string());
    if (literal("true")) return JsonValue::boolean(true);
    if (literal("false")) return JsonValue::boolean(false);
    if (literal("null")) return JsonValue();
    if (c == '-' || (c >= '0' && c <= '9')) return number();
    fail(std::string("unexpected character '") + c + "'");
  }

  JsonValue object(int depth) {
    ++pos_;
    JsonValue v = JsonValue::object();
    if (consume('}')) return v;
    do {
      skipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '"') fail("expected a member name");
      std::string key = string();
      if (v.find(key) != nullptr) fail("member '" + key + "' given twice");
      expect(':');
      v.members_.emplace_back(std::move(key), value(depth + 1));
    } while (consume(','));
    expect('}');
    return v;
  }

  JsonValue array(int depth) {
    ++pos_;
    JsonValue v = JsonValue::array();
    if (consume(']')) return v;
    do {
      v.items_.push_back(value(depth + 1));
    } while (consume(','));
    expect(']');
    return v;
  }

  JsonValue number() {
    const std::size_t start = pos_;
    const auto digits = [this] {
      const std::size_t from = pos_;
      while (pos_ < text_.size() && text_[pos_] >= '0' && text_[pos_] <= '9') ++pos_;
      return pos_ > from;
    };
    if (text_[pos_] == '-') ++pos_;
    if (pos_ < text_.size() && text_[pos_] == '0') {
      ++pos_;
    } else if (!digits()) {
      fail("malformed number");
    }
    if (pos_ < text_.size() && text_[pos_] == '.') {
      ++pos_;
      if (!digits()) fail("malformed number");
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
      if (!digits()) fail("malformed number");
    }
    JsonValue v;
    v.type_ = JsonValue::Type::kNumber;
    v.text_ = std::string(text_.substr(start, pos_ - start));
    return v;
  }

  unsigned hex4() {
    if (pos_ + 4 > text_.size()) fail("truncated \\u escape");
    unsigned code = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = text_[pos_++];
      code <<= 4;
      if (h >= '0' && h <= '9') {
        code |= static_cast<unsigned>(h - '0');
      } else if (h >= 'a' && h <= 'f') {
        code |= static_cast<unsigned>(h - 'a' + 10);
      } else if (h >= 'A' && h <= 'F') {
        code |= static_cast<unsigned>(h - 'A' + 10);
      } else {
        fail("bad \\u escape");
      }
    }
    return code;
  }

  static void appendUtf8(std::string& out, unsigned cp) {
    const auto byte = [&out](unsigned b) { out += static_cast<char>(b); };
    if (cp < 0x80) {
      byte(cp);
    } else if (cp < 0x800) {
      byte(0xC0 | (cp >> 6));
      byte(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      byte(0xE0 | (cp >> 12));
      byte(0x80 | ((cp >> 6) & 0x3F));
      byte(0x80 | (cp & 0x3F));
    } else {
      byte(0xF0 | (cp >> 18));
      byte(0x80 | ((cp >> 12) & 0x3F));
      byte(0x80 | ((cp >> 6) & 0x3F));
      byte(0x80 | (cp & 0x3F));
    }
  }

  std::string string() {
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (pos_ >= text_.size()) fail("unterminated string");
      const char c = text_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size()) fail("unterminated string");
      const char e = text_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00) {
            if (!literal("\\u")) fail("unpaired surrogate");
            const unsigned low = hex4();
            if (low < 0xDC00 || low >= 0xE000) fail("unpaired surrogate");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
          } else if (cp >= 0xDC00 && cp < 0xE000) {
            fail("unpaired surrogate");
          }
          appendUtf8(out, cp);
          break;
        }
        default: fail(std::string("bad escape '\\") + e + "'");
      }
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

JsonValue JsonValue::boolean(bool value) {
  JsonValue v;
  v.type_ = Type::kBool;
  v.bool_ = value;
  return v;
}

JsonValue JsonValue::number(double value) {
  JsonValue v;
  if (!std::isfinite(value)) return v;
  v.type_ = Type::kNumber;
  v.text_ = monitor::formatNumber(value);
  return v;
}

JsonValue JsonValue::integer(std::int64_t value) {
  JsonValue v;
  v.type_ = Type::kNumber;
  v.text_ = std::to_string(value);
  return v;
}

JsonValue JsonValue::unsignedInteger(std::uint64_t value) {
  JsonValue v;
  v.type_ = Type::kNumber;
  v.text_ = std::to_string(value);
  return v;
}

JsonValue JsonValue::string(std::string value) {
  JsonValue v;
  v.type_ = Type::kString;
  v.text_ = std::move(value);
  return v;
}

JsonValue JsonValue::array() {
  JsonValue v;
  v.type_ = Type::kArray;
  return v;
}

JsonValue JsonValue::object() {
  JsonValue v;
  v.type_ = Type::kObject;
  return v;
}

JsonValue JsonValue::parse(std::string_view text) { return JsonParser(text).document(); }

std::optional<bool> JsonValue::asBool() const {
  if (type_ != Type::kBool) return std::nullopt;
  return bool_;
}

std::optional<double> JsonValue::asNumber() const {
  if (type_ != Type::kNumber) return std::nullopt;
  errno = 0;
  const double v = std::strtod(text_.c_str(), nullptr);
  if (errno == ERANGE && std::isinf(v)) return std::nullopt;  // 1e999: not a finite number
  return v;
}

std::optional<std::string> JsonValue::asString() const {
  if (type_ != Type::kString) return std::nullopt;
  return text_;
}

std::optional<std::int64_t> JsonValue::asInteger() const {
  if (type_ != Type::kNumber || text_.find_first_of(".eE") != std::string::npos) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text_.c_str(), &end, 10);
  if (errno != 0 || end != text_.c_str() + text_.size()) return std::nullopt;
  return static_cast<std::int64_t>(v);
}

std::optional<std::uint64_t> JsonValue::asUnsigned() const {
  if (type_ != Type::kNumber || text_.empty() || text_.front() == '-' ||
      text_.find_first_of(".eE") != std::string::npos) {
    return std::nullopt;
  }
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text_.c_str(), &end, 10);
  if (errno != 0 || end != text_.c_str() + text_.size()) return std::nullopt;
  return static_cast<std::uint64_t>(v);
}

const JsonValue* JsonValue::find(std::string_view key) const {
  for (const auto& [k, v] : members_) {
    if (k == key) return &v;
  }
  return nullptr;
}

JsonValue& JsonValue::set(const std::string& key, JsonValue value) {
  for (auto& [k, v] : members_) {
    if (k == key) {
      v = std::move(value);
      return *this;
    }
  }
  members_.emplace_back(key, std::move(value));
  return *this;
}

JsonValue& JsonValue::push(JsonValue value) {
  items_.push_back(std::move(value));
  return *this;
}

bool JsonValue::flat() const {
  for (const JsonValue& v : items_) {
    if (v.isArray() || v.isObject()) return false;
  }
  for (const auto& [k, v] : members_) {
    if (v.isArray() || v.isObject()) return false;
  }
  return true;
}

void JsonValue::dumpTo(std::string& out, int depth) const {
  switch (type_) {
    case Type::kNull: out += "null"; return;
    case Type::kBool: out += bool_ ? "true" : "false"; return;
    case Type::kNumber: out += text_; return;
    case Type::kString: out += monitor::jsonQuote(text_); return;
    case Type::kArray:
    case Type::kObject: break;
  }
  const bool is_object = type_ == Type::kObject;
  const std::size_t n = is_object ? members_.size() : items_.size();
  out += is_object ? '{' : '[';
  if (n == 0) {
    out += is_object ? '}' : ']';
    return;
  }
  // A top-level container is always broken into lines, so even a flat summary reads one key per line.
  const bool one_line = depth > 0 && flat();
  const std::string indent(static_cast<std::size_t>(2 * (depth + 1)), ' ');
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) out += one_line ? ", " : ",";
    if (!one_line) out += "\n" + indent;
    if (is_object) {
      out += monitor::jsonQuote(members_[k].first) + ": ";
      members_[k].second.dumpTo(out, depth + 1);
    } else {
      items_[k].dumpTo(out, depth + 1);
    }
  }
  if (!one_line) out += "\n" + std::string(static_cast<std::size_t>(2 * depth), ' ');
  out += is_object ? '}' : ']';
}

std::string JsonValue::dump() const {
  std::string out;
  dumpTo(out, 0);
  out += '\n';
  return out;
}

}  // namespace swa::monitor_node
