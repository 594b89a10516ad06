#include "io/json.hpp"

#include <fmt/format.h>

#include <cmath>

namespace sablier {

std::string json_quote(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(c)));
        else
          out += c;
    }
  }
  return out + "\"";
}

JsonObject& JsonObject::str(const std::string& key, const std::string& value) {
  members_.emplace_back(key, json_quote(value));
  return *this;
}

// Shortest text that reads back to the same double; JSON has no NaN or
// infinity, so those become null.
JsonObject& JsonObject::num(const std::string& key, double value) {
  members_.emplace_back(key, std::isfinite(value) ? fmt::format("{}", value) : "null");
  return *this;
}

JsonObject& JsonObject::integer(const std::string& key, long long value) {
  members_.emplace_back(key, std::to_string(value));
  return *this;
}

JsonObject& JsonObject::boolean(const std::string& key, bool value) {
  members_.emplace_back(key, value ? "true" : "false");
  return *this;
}

JsonObject& JsonObject::null(const std::string& key) {
  members_.emplace_back(key, "null");
  return *this;
}

JsonObject& JsonObject::object(const std::string& key, const JsonObject& value) {
  members_.emplace_back(key, value.dump_inline());
  return *this;
}

std::string JsonObject::dump() const {
  std::string out = "{\n";
  for (std::size_t i = 0; i < members_.size(); ++i)
    out += "  " + json_quote(members_[i].first) + ": " + members_[i].second +
           (i + 1 < members_.size() ? ",\n" : "\n");
  return out + "}\n";
}

std::string JsonObject::dump_inline() const {
  std::string out = "{";
  for (std::size_t i = 0; i < members_.size(); ++i)
    out += (i ? ", " : "") + json_quote(members_[i].first) + ": " + members_[i].second;
  return out + "}";
}

}  // namespace sablier
