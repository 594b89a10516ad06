// Strict reading of one TOML table: typed getters with ranges, every error a
// one-line SceneError `<where>: <dotted.key>: <what is wrong>; <what is
// allowed>`, where <where> is `file:line`, `file` or `--set`. Keys present
// but never read are reported as unknown, with the closest known key
// suggested.
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

// Where a node came from: "file:line", or `fallback` when it has no line.
std::string where(const toml::source_region& src, const std::string& fallback);

// The candidate the key most likely misspells: the only one it begins, or
// the closest by edit distance (empty if none is close).
std::string closest_key(const std::string& key, const std::vector<std::string>& candidates);

// "\"a\", \"b\", \"c\""
std::string quoted_list(const std::vector<std::string>& words);

// An interval of allowed values; either end may be open or absent.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  // "0 <= mu <= 5", "fps > 0", "any finite number"
  std::string text(const std::string& name) const;
  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
};

class TableReader {
 public:
  // The --set override that set a dotted key (as full() names it, "sand[0].radius"),
  // or that created a table to hold one (`created`: the table's other keys are
  // the file's defaults, not the override's).
  struct Override {
    std::string text;  // "sand.0.radius=0.15", as given
    bool created = false;
  };
  using Origins = std::map<std::string, Override>;

  // `table` may be null (an absent optional table: every key takes its default).
  TableReader(const toml::table* table, std::string prefix, std::string file,
              const Origins* origins = nullptr);
  // A reader for another table (an element of an array of tables), sharing
  // file and origins.
  TableReader sub(const toml::table* table, const std::string& prefix) const {
    return TableReader(table, prefix, file_, origins_);
  }
  // A reader for the sub-table `key` (absent: an empty reader, which still
  // knows where the table was looked for, to suggest a misspelt one).
  TableReader child(const std::string& key);

  bool has(const std::string& key) const { return table_ && table_->contains(key); }
  // The node (null if absent); marks the key as known.
  const toml::node* node(const std::string& key);

  // Getters: no fallback means the key is required.
  double number(const std::string& key, std::optional<double> fallback, const Range& range);
  long integer(const std::string& key, std::optional<long> fallback, const Range& range);
  // An integer that must also fit an int.
  int int_value(const std::string& key, std::optional<int> fallback, const Range& range);
  std::string choice(const std::string& key, std::optional<std::string> fallback,
                     const std::vector<std::string>& allowed);
  // `n` finite numbers (or integers), each in `range`; components past `n` are 0.
  Vec3d vector(const std::string& key, int n, std::optional<Vec3d> fallback, const Range& range);
  Vec3i integers(const std::string& key, int n, std::optional<Vec3i> fallback, const Range& range);
  // An array of tables ([[key]] blocks); null if absent, possibly empty.
  const toml::array* array_of_tables(const std::string& key);
  // f(reader) for each table of such an array, in order, the reader of
  // table k named `prefix[k]` in messages.
  template <class F>
  void for_each_table(const toml::array& list, const std::string& prefix, F&& f) const {
    for (std::size_t k = 0; k < list.size(); ++k)
      f(sub(list.get(k)->as_table(), prefix + "[" + std::to_string(k) + "]"));
  }

  // Throws for keys present in the table but neither read nor in `known`.
  void reject_unknown(const std::vector<std::string>& known = {}) const;

  // A required key is absent: "missing; required: <required>", unless the
  // table (or, when the table itself is absent, its parent) has an unknown
  // key that is a likely misspelling of it: then that key is reported, at
  // its line, with the right name suggested.
  [[noreturn]] void fail_missing(const std::string& key, const std::string& required) const;
  // At `n` (the table's line when null). `with` names, as full() does, the
  // other keys a check across keys read ("grid.size", full("radius"), or a
  // whole table): those that --set gave are named after the message,
  // "(with --set sand.0.radius=0.15)", since the line blamed is the file's.
  [[noreturn]] void fail_at(const toml::node* n, const std::string& key, const std::string& what,
                            const std::vector<std::string>& with = {}) const;
  std::string full(const std::string& key) const {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }
  const std::string& prefix() const { return prefix_; }

 private:
  const toml::node* required(const std::string& key, bool have_fallback,
                             const std::string& allowed);
  const toml::array* array(const std::string& key, int n, bool have_fallback,
                           const std::string& allowed);
  double finite_number(const toml::node* n, const std::string& key,
                       const std::string& allowed) const;
  long whole_number(const toml::node* n, const std::string& key, const std::string& allowed) const;
  void check_range(const toml::node* n, const std::string& key, double v, const Range& range,
                   const std::string& prefix) const;
  std::string location(const toml::source_region& src, const std::string& dotted) const;
  const Override* override_of(const std::string& dotted) const;
  void fail_misspelt(const toml::table& table, const std::string& prefix, const std::string& name,
                     const std::string& what) const;

  const toml::table* table_;
  std::string prefix_, file_;
  const Origins* origins_;
  std::set<std::string> read_;
  // An absent table's parent, and the parent's prefix, where it was looked for.
  const toml::table* parent_ = nullptr;
  std::string parent_prefix_;
};

// Keys that the scene's dimension or shape does not use are errors, not
// silently ignored: the first of `keys` present fails with `why` (`with`:
// the keys that made it unused, as for fail_at).
void reject_keys(TableReader& t, const std::vector<std::string>& keys, const std::string& why,
                 const std::vector<std::string>& with = {});

// A required choice among `here`; a value that is valid only in the other
// dimension (`elsewhere`) gets a message saying so.
std::string dimension_choice(TableReader& t, const std::string& key,
                             const std::vector<std::string>& here,
                             const std::vector<std::string>& elsewhere, int dimension);

}  // namespace sablier
