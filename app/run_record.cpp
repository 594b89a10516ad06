#include "run_record.hpp"

#include <unistd.h>

#include <ctime>

#include "io/hash.hpp"
#include "io/json.hpp"

namespace sablier {
namespace {

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

std::string compiler() {
#if defined(__clang__)
  return __VERSION__;  // "Clang 15.0.7 ..."
#elif defined(__GNUC__)
  return "GCC " __VERSION__;
#else
  return "unknown";
#endif
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

}  // namespace

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string format_run_json(const RunRecord& r) {
  JsonObject seconds;
  seconds.num("transfer", r.transfer)
      .num("assembly", r.assembly)
      .num("solve", r.solve)
      .num("advection", r.advection)
      .num("total", r.transfer + r.assembly + r.solve + r.advection);
  JsonObject o;
  o.str("status", r.status)
      .str("program", "sablier")
      .str("version", SABLIER_VERSION)
      .str("build_type", SABLIER_BUILD_TYPE)
      .str("compiler", compiler())
      .str("hostname", host_name())
      .integer("threads", r.threads)
      .str("started", r.started);
  if (r.ended.empty())
    o.null("ended");
  else
    o.str("ended", r.ended);
  if (r.resumed_from_step < 0)
    o.null("resumed_from_step");
  else
    o.integer("resumed_from_step", r.resumed_from_step);
  o.integer("steps", r.steps)
      .num("time", r.time)
      .integer("frames_written", r.frames_written)
      .integer("frames", r.frames)
      .str("formats", join(r.formats))
      .boolean("compress", r.compress)
      .boolean("grid", r.grid)
      .object("seconds", seconds)
      .str("scene_hash", hash_hex(r.scene_hash))
      .str("scene", r.scene_text);
  return o.dump();
}

}  // namespace sablier
