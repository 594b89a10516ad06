// run.json: valid JSON (read back by a small parser here), written when the
// run starts and rewritten when it ends, with the resolved scene and its hash.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <map>
#include <memory>

#include "io/hash.hpp"
#include "io/json.hpp"
#include "io/stats_writer.hpp"
#include "io/writers.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;

// A JSON value: strings and numbers kept as text (numbers as written),
// objects as maps. Enough to check run.json; throws on malformed input.
struct Json {
  enum Kind { Null, Bool, Number, String, Object } kind = Null;
  std::string text;
  std::map<std::string, Json> members;
  const Json& operator[](const std::string& key) const { return members.at(key); }
};

class JsonParser {
 public:
  explicit JsonParser(const std::string& s) : s_(s) {}
  Json document() {
    Json v = value();
    skip();
    if (i_ != s_.size()) fail("trailing text");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error(what + " at byte " + std::to_string(i_));
  }
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(const std::string& word) {
    if (s_.compare(i_, word.size(), word) != 0) return false;
    i_ += word.size();
    return true;
  }
  Json value() {
    skip();
    Json v;
    if (i_ >= s_.size()) fail("end of text");
    if (s_[i_] == '{') return object();
    if (s_[i_] == '"') {
      v.kind = Json::String;
      v.text = string();
    } else if (eat("null")) {
      v.kind = Json::Null;
    } else if (eat("true") || eat("false")) {
      v.kind = Json::Bool;
      v.text = s_[i_ - 1] == 'e' && s_[i_ - 2] == 'u' ? "true" : "false";
    } else {
      const std::size_t start = i_;
      while (i_ < s_.size() && std::strchr("+-.0123456789eE", s_[i_])) ++i_;
      if (i_ == start) fail("unexpected character");
      v.kind = Json::Number;
      v.text = s_.substr(start, i_ - start);
    }
    return v;
  }
  Json object() {
    Json v;
    v.kind = Json::Object;
    ++i_;
    skip();
    if (eat("}")) return v;
    while (true) {
      skip();
      const std::string key = string();
      skip();
      if (!eat(":")) fail("expected ':'");
      v.members[key] = value();
      skip();
      if (eat("}")) return v;
      if (!eat(",")) fail("expected ',' or '}'");
    }
  }
  std::string string() {
    if (!eat("\"")) fail("expected a string");
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      const char c = s_[i_++];
      if (static_cast<unsigned char>(c) < 0x20) fail("raw control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      const char e = s_[i_++];
      const char* from = "\"\\/bfnrt";
      const char* to = "\"\\/\b\f\n\r\t";
      if (const char* k = std::strchr(from, e); k && e) {
        out += to[k - from];
      } else if (e == 'u') {
        out += static_cast<char>(std::stoi(s_.substr(i_, 4), nullptr, 16));  // ASCII only
        i_ += 4;
      } else {
        fail("bad escape");
      }
    }
    if (!eat("\"")) fail("unterminated string");
    return out;
  }

  const std::string& s_;
  std::size_t i_ = 0;
};

Json parse(const std::string& text) { return JsonParser(text).document(); }

TEST(RunJson, QuotingRoundTrips) {
  const std::string nasty = std::string("a\"b\\c\nd\te\x01 f\x1f") + "\xc3\xa9";
  JsonObject o;
  o.str("s", nasty)
      .num("inf", 1.0 / 0.0)
      .num("x", 0.1)
      .integer("n", -3)
      .boolean("b", true)
      .null("z");
  JsonObject outer;
  outer.object("o", o).str("k\"ey", "v");
  const Json j = parse(outer.dump());
  EXPECT_EQ(j["o"]["s"].text, nasty);
  EXPECT_EQ(j["o"]["inf"].kind, Json::Null);  // JSON has no infinity
  EXPECT_EQ(std::stod(j["o"]["x"].text), 0.1);
  EXPECT_EQ(j["o"]["n"].text, "-3");
  EXPECT_EQ(j["o"]["b"].text, "true");
  EXPECT_EQ(j["k\"ey"].text, "v");
}

TEST(RunJson, DescribesTheRun) {
  const fs::path dir = test::fresh_dir("runjson");
  const std::string cmd = std::string(SABLIER_BINARY) + " run " + SABLIER_SOURCE_DIR +
                          "/scenes/collapse2d.toml --out " + dir.string() +
                          " --set time.frames=2 --set grid.resolution=[40,10] --threads 1 --quiet";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const Json j = parse(read_file((dir / "run.json").string()));
  EXPECT_EQ(j["status"].text, "finished");
  EXPECT_EQ(j["version"].text, SABLIER_VERSION);
  EXPECT_EQ(j["build_type"].text, SABLIER_BUILD_TYPE);
  EXPECT_FALSE(j["compiler"].text.empty());
  EXPECT_EQ(j["hostname"].kind, Json::String);
  EXPECT_EQ(j["threads"].text, "1");
  for (const char* t : {"started", "ended"}) {
    const std::string s = j[t].text;  // 2024-05-01T12:34:56Z
    ASSERT_EQ(s.size(), 20u) << s;
    EXPECT_EQ(s[10], 'T');
    EXPECT_EQ(s.back(), 'Z');
  }
  const std::string scene_text = read_file((dir / "scene.toml").string());
  EXPECT_EQ(j["scene"].text, scene_text);
  EXPECT_EQ(j["scene_hash"].text, hash_hex(fnv1a64(scene_text)));
  const auto rows = parse_stats_csv(read_file((dir / "stats.csv").string()));
  EXPECT_EQ(j["steps"].text, std::to_string(rows.size()));
  EXPECT_EQ(j["frames_written"].text, "3");  // frames 0, 1, 2
  double solve = 0.0;
  for (const StepStats& s : rows) solve += s.solve_seconds;
  EXPECT_NEAR(std::stod(j["seconds"]["solve"].text), solve, 1e-9 * (1 + solve));
  for (const char* phase : {"transfer", "assembly", "advection", "total"})
    EXPECT_EQ(j["seconds"][phase].kind, Json::Number) << phase;
  EXPECT_EQ(j["resumed_from_step"].kind, Json::Null);
  fs::remove_all(dir);
}

TEST(RunJson, Fnv1a64KnownValues) {
  // Reference values of the 64-bit FNV-1a hash.
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(hash_hex(fnv1a64("foobar")), "85944171f73967e8");
}

}  // namespace
}  // namespace sablier
