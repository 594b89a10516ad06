// Just enough JSON writing for run.json, without a dependency: an object
// whose values are strings, numbers, booleans, null or nested objects, keys
// kept in the order they were added.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace sablier {

// `s` as a JSON string literal: quoted, with '"', '\\' and control
// characters escaped (RFC 8259); other bytes (UTF-8) pass through.
std::string json_quote(const std::string& s);

class JsonObject {
 public:
  JsonObject& str(const std::string& key, const std::string& value);
  JsonObject& num(const std::string& key, double value);  // non-finite -> null
  JsonObject& integer(const std::string& key, long long value);
  JsonObject& boolean(const std::string& key, bool value);
  JsonObject& null(const std::string& key);
  JsonObject& object(const std::string& key, const JsonObject& value);

  // One key per line, indented by two spaces per level; nested objects on
  // one line.
  std::string dump() const;
  std::string dump_inline() const;

 private:
  std::vector<std::pair<std::string, std::string>> members_;  // key, JSON text
};

}  // namespace sablier
