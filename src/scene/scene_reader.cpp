#include "scene/scene_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace sablier {
namespace {

// A float as TOML writes it: 40.0, not 40.
std::string float_text(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEni") == std::string::npos) s += ".0";
  return s;
}

// What a node holds, for "expected X, found Y" messages.
std::string describe(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return fmt::format("the string \"{}\"", n.as_string()->get());
    case toml::node_type::integer:
      return fmt::format("the integer {}", n.as_integer()->get());
    case toml::node_type::floating_point:
      return "the float " + float_text(n.as_floating_point()->get());
    case toml::node_type::boolean:
      return fmt::format("the boolean {}", n.as_boolean()->get());
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    default:
      return "a date or time";
  }
}

// "sand[0].jitter" -> "sand[0]" -> "sand" -> "".
std::string parent_key(const std::string& key) {
  const std::size_t p = key.find_last_of(".[");
  return p == std::string::npos ? std::string() : key.substr(0, p);
}

// Whether the dotted key `inner` lies within `outer`: "sand[0].radius" within
// "sand[0]" and "sand".
bool within(const std::string& inner, const std::string& outer) {
  return inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
         (inner[outer.size()] == '.' || inner[outer.size()] == '[');
}

// The names known_scene_keys() gives in the table `prefix` ("", "grid",
// "sand[2]", "sand[0].mu_i"): "size" in "grid", "sand" at the top level.
std::vector<std::string> keys_known_in(const std::string& prefix) {
  std::string pattern;  // "sand[2].mu_i" -> "sand[].mu_i", as known_scene_keys() has it
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    pattern += prefix[i];
    if (prefix[i] == '[') i = prefix.find(']', i) - 1;
  }
  if (!pattern.empty()) pattern += '.';
  static const std::vector<std::string> all = known_scene_keys();
  std::vector<std::string> names;
  for (const std::string& k : all)
    if (k.compare(0, pattern.size(), pattern) == 0)
      names.push_back(
          k.substr(pattern.size(), k.find_first_of(".[", pattern.size()) - pattern.size()));
  return names;
}

std::string component_name(int k) { return fmt::format("component {} ({}) = ", k, "xyz"[k]); }

// "file:7: material.mu: what", or "--set material.mu: what" for overrides.
SceneError scene_error(const std::string& loc, const std::string& key, const std::string& what) {
  return SceneError(fmt::format("{}{} {}: {}", loc, loc == "--set" ? "" : ":", key, what));
}

}  // namespace

std::string where(const toml::source_region& src, const std::string& fallback) {
  const std::string path = src.path ? *src.path : fallback;
  if (path == "--set" || src.begin.line == 0) return path;
  return fmt::format("{}:{}", path, src.begin.line);
}

std::string closest_key(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  if (key.empty()) return best;
  // A key that begins exactly one candidate ("fr" for "frames") is that one.
  int starts = 0;
  for (const std::string& c : candidates)
    if (c.size() > key.size() && c.compare(0, key.size(), key) == 0) {
      best = c;
      ++starts;
    }
  if (starts == 1) return best;
  best.clear();
  // Otherwise the nearest by edit distance, at most a third of the key's
  // length (2 for short keys), and less than the key's length: a one-letter
  // key is not a misspelling of any two-letter one ("f" is not "cfl").
  std::size_t best_d = std::min(std::max<std::size_t>(2, key.size() / 3), key.size() - 1) + 1;
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

std::string quoted_list(const std::vector<std::string>& words) {
  return fmt::format("\"{}\"", fmt::join(words, "\", \""));
}

std::string Range::text(const std::string& name) const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  const char* below = lo_open ? "<" : "<=";
  const char* above = hi_open ? "<" : "<=";
  if (has_lo && has_hi) return fmt::format("{} {} {} {} {}", lo, below, name, above, hi);
  if (has_lo) return fmt::format("{} {} {}", name, lo_open ? ">" : ">=", lo);
  if (has_hi) return fmt::format("{} {} {}", name, above, hi);
  return "any finite number";
}

TableReader::TableReader(const toml::table* table, std::string prefix, std::string file,
                         const Origins* origins)
    : table_(table), prefix_(std::move(prefix)), file_(std::move(file)), origins_(origins) {}

TableReader TableReader::child(const std::string& key) {
  const toml::node* n = node(key);
  if (n && !n->is_table())
    fail_at(
        n, key,
        fmt::format("expected a table, found {}; allowed: a [{}] table", describe(*n), full(key)));
  TableReader c = sub(n ? n->as_table() : nullptr, full(key));
  if (!n) c.parent_ = table_, c.parent_prefix_ = prefix_;
  return c;
}

// The override that gave `dotted` or a table above it (null if none).
const TableReader::Override* TableReader::override_of(const std::string& dotted) const {
  if (!origins_) return nullptr;
  for (std::string k = dotted; !k.empty(); k = parent_key(k)) {
    const auto it = origins_->find(k);
    if (it != origins_->end()) return &it->second;
  }
  return nullptr;
}

// A value given by --set (or inside one) is reported as `--set`, else file:line.
std::string TableReader::location(const toml::source_region& src, const std::string& dotted) const {
  return override_of(dotted) ? "--set" : where(src, file_);
}

void TableReader::fail_at(const toml::node* n, const std::string& key, const std::string& what,
                          const std::vector<std::string>& with) const {
  // Without a node, the table's line (none for the top level).
  const toml::source_region none{};
  const toml::source_region& src = n                            ? n->source()
                                   : table_ && !prefix_.empty() ? table_->source()
                                                                : none;
  const Override* blamed = override_of(full(key));
  std::vector<std::string> texts;
  if (origins_)
    for (const auto& [dotted, o] : *origins_) {
      // A table --set created holds the file's defaults, not the override's
      // values; the blamed key's own override is named already.
      if (o.created || &o == blamed) continue;
      const bool read = std::any_of(with.begin(), with.end(), [&](const std::string& w) {
        return w == dotted || within(w, dotted) || within(dotted, w);
      });
      if (read && std::find(texts.begin(), texts.end(), o.text) == texts.end())
        texts.push_back(o.text);
    }
  const std::string also =
      texts.empty() ? "" : fmt::format(" (with --set {})", fmt::join(texts, ", --set "));
  throw scene_error(location(src, full(key)), full(key), what + also);
}

void TableReader::fail_misspelt(const toml::table& table, const std::string& prefix,
                                const std::string& name, const std::string& what) const {
  const std::vector<std::string> known = keys_known_in(prefix);
  std::vector<std::string> unknown;
  for (const auto& [k, v] : table)
    if (std::find(known.begin(), known.end(), k.str()) == known.end())
      unknown.emplace_back(k.str());
  const std::string typo = closest_key(name, unknown);
  if (typo.empty()) return;
  const std::string dotted = prefix.empty() ? typo : prefix + "." + typo;
  throw scene_error(location(table.get(typo)->source(), dotted), dotted,
                    fmt::format("unknown key \"{}\"; did you mean \"{}\"? ({})", typo, name, what));
}

void TableReader::fail_missing(const std::string& key, const std::string& required) const {
  const std::string what = "missing; required: " + required;
  if (table_) fail_misspelt(*table_, prefix_, key, full(key) + " is " + what);
  if (parent_) {
    const std::string name = prefix_.substr(parent_prefix_.empty() ? 0 : parent_prefix_.size() + 1);
    fail_misspelt(*parent_, parent_prefix_, name, full(key) + " is " + what);
  }
  fail_at(nullptr, key, what);
}

const toml::node* TableReader::node(const std::string& key) {
  read_.insert(key);
  return table_ ? table_->get(key) : nullptr;
}

const toml::node* TableReader::required(const std::string& key, bool have_fallback,
                                        const std::string& allowed) {
  const toml::node* n = node(key);
  if (!n && !have_fallback) fail_missing(key, allowed);
  return n;
}

double TableReader::finite_number(const toml::node* n, const std::string& key,
                                  const std::string& allowed) const {
  double v = 0.0;
  if (const auto* i = n->as_integer()) {
    v = static_cast<double>(i->get());
  } else if (const auto* f = n->as_floating_point()) {
    v = f->get();
  } else {
    fail_at(n, key, fmt::format("expected a number, found {}; allowed: {}", describe(*n), allowed));
  }
  if (!std::isfinite(v))
    fail_at(n, key, fmt::format("{} is not a finite number; allowed: {}", v, allowed));
  return v;
}

long TableReader::whole_number(const toml::node* n, const std::string& key,
                               const std::string& allowed) const {
  if (!n->is_integer())
    fail_at(n, key,
            fmt::format("expected an integer, found {}; allowed: {}", describe(*n), allowed));
  return static_cast<long>(n->as_integer()->get());
}

void TableReader::check_range(const toml::node* n, const std::string& key, double v,
                              const Range& range, const std::string& prefix) const {
  if (!range.contains(v))
    fail_at(n, key, fmt::format("{}{} is out of range; allowed: {}", prefix, v, range.text(key)));
}

double TableReader::number(const std::string& key, std::optional<double> fallback,
                           const Range& range) {
  const std::string allowed = range.text(key);
  const toml::node* n = required(key, fallback.has_value(), "a number, " + allowed);
  if (!n) return *fallback;
  const double v = finite_number(n, key, allowed);
  check_range(n, key, v, range, "");
  return v;
}

long TableReader::integer(const std::string& key, std::optional<long> fallback,
                          const Range& range) {
  const std::string allowed = "an integer, " + range.text(key);
  const toml::node* n = required(key, fallback.has_value(), allowed);
  if (!n) return *fallback;
  const long v = whole_number(n, key, allowed);
  if (!range.contains(static_cast<double>(v)))
    fail_at(n, key, fmt::format("{} is out of range; allowed: {}", v, allowed));
  return v;
}

int TableReader::int_value(const std::string& key, std::optional<int> fallback,
                           const Range& range) {
  const long v = integer(key, fallback, range);
  constexpr int kMax = std::numeric_limits<int>::max();
  if (v > kMax)
    fail_at(node(key), key, fmt::format("{} is too large; allowed: {} <= {}", v, key, kMax));
  return static_cast<int>(v);
}

std::string TableReader::choice(const std::string& key, std::optional<std::string> fallback,
                                const std::vector<std::string>& allowed) {
  const std::string list = quoted_list(allowed);
  const toml::node* n = required(key, fallback.has_value(), "one of " + list);
  if (!n) return *fallback;
  if (!n->is_string())
    fail_at(n, key, fmt::format("expected a string, found {}; allowed: {}", describe(*n), list));
  const std::string v = n->as_string()->get();
  if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
    fail_at(n, key, fmt::format("\"{}\" is not allowed; allowed: {}", v, list));
  return v;
}

const toml::array* TableReader::array(const std::string& key, int n, bool have_fallback,
                                      const std::string& allowed) {
  const toml::node* node = required(key, have_fallback, allowed);
  if (!node) return nullptr;
  const toml::array* a = node->as_array();
  if (!a)
    fail_at(node, key,
            fmt::format("expected an array, found {}; allowed: {}", describe(*node), allowed));
  if (static_cast<int>(a->size()) != n)
    fail_at(node, key,
            fmt::format("expected {} components (one per axis), found {}; allowed: {}", n,
                        a->size(), allowed),
            {"dimension"});
  return a;
}

Vec3d TableReader::vector(const std::string& key, int n, std::optional<Vec3d> fallback,
                          const Range& range) {
  const bool any = !std::isfinite(range.lo) && !std::isfinite(range.hi);
  const std::string allowed =
      any ? fmt::format("an array of {} finite numbers", n)
          : fmt::format("an array of {} numbers, each {}", n, range.text(key));
  const toml::array* a = array(key, n, fallback.has_value(), allowed);
  if (!a) return *fallback;
  Vec3d v{0, 0, 0};
  for (int k = 0; k < n; ++k) {
    v[k] = finite_number(a->get(k), key, allowed);
    check_range(a->get(k), key, v[k], range, component_name(k));
  }
  return v;
}

Vec3i TableReader::integers(const std::string& key, int n, std::optional<Vec3i> fallback,
                            const Range& range) {
  const std::string allowed = fmt::format("an array of {} integers, each {}", n, range.text(key));
  const toml::array* a = array(key, n, fallback.has_value(), allowed);
  if (!a) return *fallback;
  Vec3i v{0, 0, 0};
  for (int k = 0; k < n; ++k) {
    const long x = whole_number(a->get(k), key, allowed);
    check_range(a->get(k), key, static_cast<double>(x), range, component_name(k));
    v[k] = static_cast<int>(x);
  }
  return v;
}

const toml::array* TableReader::array_of_tables(const std::string& key) {
  const toml::node* n = node(key);
  if (!n) return nullptr;
  const toml::array* a = n->as_array();
  if (!a || !(a->empty() || a->is_array_of_tables()))
    fail_at(n, key,
            fmt::format("expected [[{0}]] blocks, found {1}; allowed: [[{0}]] blocks (tables)",
                        full(key), describe(*n)));
  return a;
}

void TableReader::reject_unknown(const std::vector<std::string>& known) const {
  if (!table_) return;
  std::set<std::string> names = read_;
  names.insert(known.begin(), known.end());
  const std::vector<std::string> candidates(names.begin(), names.end());
  for (const auto& [k, v] : *table_) {
    const std::string key(k.str());
    if (std::find(candidates.begin(), candidates.end(), key) != candidates.end()) continue;
    const std::string guess = closest_key(key, candidates);
    fail_at(&v, key,
            guess.empty() ? fmt::format("unknown key \"{}\"; allowed here: {}", key,
                                        fmt::join(candidates, ", "))
                          : fmt::format("unknown key \"{}\"; did you mean \"{}\"?", key, guess));
  }
}

void reject_keys(TableReader& t, const std::vector<std::string>& keys, const std::string& why,
                 const std::vector<std::string>& with) {
  for (const std::string& k : keys)
    if (t.has(k)) t.fail_at(t.node(k), k, why, with);
}

std::string dimension_choice(TableReader& t, const std::string& key,
                             const std::vector<std::string>& here,
                             const std::vector<std::string>& elsewhere, int dimension) {
  const toml::node* n = t.node(key);
  if (n && n->is_string() && std::count(elsewhere.begin(), elsewhere.end(), n->as_string()->get()))
    t.fail_at(
        n, key,
        fmt::format("\"{}\" is only valid in {} scenes; allowed in {}D: {}", n->as_string()->get(),
                    dimension == 2 ? "3D" : "2D", dimension, quoted_list(here)),
        {"dimension"});
  return t.choice(key, std::nullopt, here);
}

}  // namespace sablier
