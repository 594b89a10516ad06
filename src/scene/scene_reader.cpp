#include "scene/scene_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sablier {

std::string where(const toml::source_region& src, const std::string& fallback) {
  const std::string path = src.path ? *src.path : fallback;
  if (path.rfind("--set", 0) == 0) return path;
  if (src.begin.line > 0) return fmt::format("{}:{}", path, src.begin.line);
  return path;
}

std::string closest_key(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, key.size() / 3) + 1;
  for (const std::string& c : candidates) {
    std::vector<std::size_t> row(c.size() + 1);
    for (std::size_t j = 0; j <= c.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= key.size(); ++i) {
      std::size_t diag = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= c.size(); ++j) {
        const std::size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (key[i - 1] != c[j - 1])});
        diag = up;
      }
    }
    if (row[c.size()] < best_d) best_d = row[c.size()], best = c;
  }
  return best;
}

std::string Range::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  std::string s;
  if (has_lo) s += fmt::format("{} {} ", lo, lo_open ? "<" : "<=");
  s += "value";
  if (has_hi) s += fmt::format(" {} {}", hi_open ? "<" : "<=", hi);
  return has_lo || has_hi ? s : "any finite number";
}

TableReader::TableReader(const toml::table* table, std::string prefix, std::string file,
                         const Origins* origins)
    : table_(table), prefix_(std::move(prefix)), file_(std::move(file)), origins_(origins) {}

// A key given by --set is reported as that override, else file:line.
std::string TableReader::location(const toml::source_region& src, const std::string& key) const {
  if (origins_) {
    const auto it = origins_->find(full(key));
    if (it != origins_->end()) return it->second;
  }
  return where(src, file_);
}

void TableReader::fail(const std::string& key, const std::string& what) const {
  const std::string loc = table_ ? location(table_->source(), key) : file_;
  throw SceneError(fmt::format("{}: {}: {}", loc, full(key), what));
}

void TableReader::fail_at(const toml::node* n, const std::string& key,
                          const std::string& what) const {
  throw SceneError(fmt::format("{}: {}: {}", location(n->source(), key), full(key), what));
}

const toml::node* TableReader::node(const std::string& key) {
  read_.insert(key);
  return table_ ? table_->get(key) : nullptr;
}

const toml::node* TableReader::required(const std::string& key, bool have_fallback) {
  const toml::node* n = node(key);
  if (!n && !have_fallback) fail(key, "missing; this key is required");
  return n;
}

double TableReader::finite_number(const toml::node* n, const std::string& key) const {
  double v;
  if (n->is_integer()) {
    v = static_cast<double>(n->as_integer()->get());
  } else if (n->is_floating_point()) {
    v = n->as_floating_point()->get();
  } else {
    fail_at(n, key, fmt::format("expected a number, found a {}", toml::impl::node_type_friendly_names[static_cast<int>(n->type())]));
  }
  if (!std::isfinite(v)) fail_at(n, key, fmt::format("{} is not a finite number", v));
  return v;
}

double TableReader::number(const std::string& key, std::optional<double> fallback,
                           const Range& range) {
  const toml::node* n = required(key, fallback.has_value());
  if (!n) return *fallback;
  const double v = finite_number(n, key);
  if (!range.contains(v))
    fail_at(n, key, fmt::format("{} is out of range; allowed: {}", v, range.text()));
  return v;
}

long TableReader::integer(const std::string& key, std::optional<long> fallback,
                          const Range& range) {
  const toml::node* n = required(key, fallback.has_value());
  if (!n) return *fallback;
  if (!n->is_integer())
    fail_at(n, key, fmt::format("expected an integer, found a {}; allowed: integer {}",
                                toml::impl::node_type_friendly_names[static_cast<int>(n->type())],
                                range.text()));
  const long v = static_cast<long>(n->as_integer()->get());
  if (!range.contains(static_cast<double>(v)))
    fail_at(n, key, fmt::format("{} is out of range; allowed: integer {}", v, range.text()));
  return v;
}

std::string TableReader::choice(const std::string& key, std::optional<std::string> fallback,
                                const std::vector<std::string>& allowed) {
  const toml::node* n = required(key, fallback.has_value());
  if (!n) return *fallback;
  const std::string list = fmt::format("\"{}\"", fmt::join(allowed, "\", \""));
  if (!n->is_string()) fail_at(n, key, "expected a string; allowed: " + list);
  const std::string v = n->as_string()->get();
  if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
    fail_at(n, key, fmt::format("\"{}\" is not allowed; allowed: {}", v, list));
  return v;
}

Vec3d TableReader::vector(const std::string& key, int count, std::optional<Vec3d> fallback,
                          const Range& range) {
  const toml::node* n = required(key, fallback.has_value());
  if (!n) return *fallback;
  const toml::array* a = n->as_array();
  if (!a || static_cast<int>(a->size()) != count)
    fail_at(n, key, fmt::format("expected an array of {} numbers (one per axis)", count));
  Vec3d v{0, 0, 0};
  for (int k = 0; k < count; ++k) {
    v[k] = finite_number(a->get(k), key);
    if (!range.contains(v[k]))
      fail_at(n, key,
              fmt::format("component {} = {} is out of range; allowed: {}", k, v[k], range.text()));
  }
  return v;
}

const toml::table* TableReader::table(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return nullptr;
  if (!n->is_table()) fail_at(n, key, "expected a table");
  return n->as_table();
}

const toml::array* TableReader::array_of_tables(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return nullptr;
  if (!n->is_array_of_tables())
    fail_at(n, key, fmt::format("expected an array of tables ([[{}]] blocks)", full(key)));
  return n->as_array();
}

void TableReader::reject_unknown(const std::vector<std::string>& known) const {
  if (!table_) return;
  std::vector<std::string> candidates(read_.begin(), read_.end());
  candidates.insert(candidates.end(), known.begin(), known.end());
  for (const auto& [k, v] : *table_) {
    const std::string key(k.str());
    if (read_.count(key) || std::find(known.begin(), known.end(), key) != known.end()) continue;
    const std::string guess = closest_key(key, candidates);
    fail_at(&v, key,
            fmt::format("unknown key{}; known keys here: {}",
                        guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess),
                        fmt::join(candidates, ", ")));
  }
}

}  // namespace sablier
