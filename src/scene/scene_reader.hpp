// Strict reading of one TOML table: typed getters with ranges, every error a
// SceneError naming the file (or the --set override), line, dotted key and
// what is allowed; keys never read are reported as unknown, with the closest
// known key suggested.
#pragma once

#include <toml++/toml.h>

#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace sablier {

// Where a node came from, for messages: "file:line" or "--set key=value".
std::string where(const toml::source_region& src, const std::string& fallback);

// Closest candidate by edit distance (empty if none is close).
std::string closest_key(const std::string& key, const std::vector<std::string>& candidates);

struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  std::string text() const;  // "0 < x <= 1" style, with x the key's last name
  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

class TableReader {
 public:
  // `origins` maps dotted keys set by --set to their override text.
  using Origins = std::map<std::string, std::string>;
  TableReader(const toml::table* table, std::string prefix, std::string file,
              const Origins* origins = nullptr);
  // A reader for a sub-table, sharing file and origins.
  TableReader sub(const toml::table* table, const std::string& prefix) const {
    return TableReader(table, prefix, file_, origins_);
  }

  bool has(const std::string& key) const { return table_ && table_->contains(key); }
  const toml::node* node(const std::string& key);

  double number(const std::string& key, std::optional<double> fallback, const Range& range);
  long integer(const std::string& key, std::optional<long> fallback, const Range& range);
  std::string choice(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& allowed);
  // A vector of `n` finite numbers, each in `range`.
  Vec3d vector(const std::string& key, int n, std::optional<Vec3d> fallback, const Range& range);
  const toml::table* table(const std::string& key);
  const toml::array* array_of_tables(const std::string& key);

  // Throws for keys present in the table but never read or allowed.
  void reject_unknown(const std::vector<std::string>& known) const;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  [[noreturn]] void fail_at(const toml::node* n, const std::string& key,
                            const std::string& what) const;
  std::string full(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }
  const std::string& file() const { return file_; }

 private:
  double finite_number(const toml::node* n, const std::string& key) const;
  const toml::node* required(const std::string& key, bool have_fallback);

  const toml::table* table_;
  std::string location(const toml::source_region& src, const std::string& key) const;

  std::string prefix_, file_;
  const Origins* origins_;
  std::set<std::string> read_;
};

}  // namespace sablier
