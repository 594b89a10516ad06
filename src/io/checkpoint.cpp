#include "io/checkpoint.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <cstring>
#include <limits>
#include <type_traits>

#include "io/bytes.hpp"
#include "io/hash.hpp"

namespace sablier {
namespace {

const char kMagic[] = "SABLIERCKPT";
constexpr std::size_t kMagicSize = sizeof kMagic - 1;
// Magic, then u32 version, u32 dimension, u64 hash, i64 steps, f64 time,
// i32 frame, i32 substep, u64 particles, u64 nodes, u32 formats length,
// u32 frame-time count.
constexpr std::size_t kHeaderBytes = kMagicSize + 4 + 4 + 8 + 8 + 8 + 4 + 4 + 8 + 8 + 4 + 4;

// Calls f(array, values per item, item count) on every array, in file order;
// one list for writing and reading keeps the two in step.
template <class C, class F>
void for_each_array(C& c, F&& f) {
  const std::uint64_t d = c.dimension, s = d * (d + 1) / 2, n = c.particles;
  f(c.position, d, n);
  f(c.velocity, d, n);
  f(c.affine, d * d, n);
  f(c.volume, 1, n);
  f(c.cohesion, 1, n);
  f(c.inertial, 1, n);
  f(c.id, 1, n);
  f(c.material, 1, n);
  f(c.stress, s, n);
  f(c.phi, 1, n);
  f(c.shear_rate, 1, n);
  f(c.warm_stress, s, c.nodes);
  if (c.version >= 4) f(c.warm_case, 1, c.nodes);
}

// File size the header announces; max() when its counts cannot fit in a
// file of `available` bytes (a corrupted header).
std::uint64_t expected_size(const Checkpoint& c, std::uint64_t available) {
  if (c.particles > available || c.nodes > available || (c.dimension != 2 && c.dimension != 3))
    return std::numeric_limits<std::uint64_t>::max();
  std::uint64_t bytes = 8 * c.frame_times.size();
  for_each_array(c, [&](const auto& v, std::uint64_t per, std::uint64_t count) {
    bytes += sizeof(typename std::remove_reference_t<decltype(v)>::value_type) * per * count;
  });
  return kHeaderBytes + c.formats.size() + bytes + 8;
}

// The trailing checksum of `n` bytes: from format 5 zlib's CRC-32 (3 ms
// on a 16.5 MB checkpoint), before it FNV-1a 64 (19 ms, one byte at a time).
std::uint64_t checksum(std::uint32_t version, const char* data, std::size_t n) {
  if (version < 5) return fnv1a64(data, n);
  return crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const unsigned char*>(data), n);
}

}  // namespace

std::string encode_checkpoint(const Checkpoint& c, const std::string& target) {
  std::string out;
  encode_checkpoint(c, target, &out);
  return out;
}

void encode_checkpoint(const Checkpoint& c, const std::string& target, std::string* out) {
  if (c.version != Checkpoint::kFormatVersion)
    throw CheckpointError(fmt::format("{}: internal error: writes format {} only, not {}", target,
                                      Checkpoint::kFormatVersion, c.version));
  out->clear();
  ByteWriter w(out);
  constexpr std::uint64_t kUnbounded = std::numeric_limits<std::uint64_t>::max();
  if (const std::uint64_t size = expected_size(c, kUnbounded); size != kUnbounded) w.reserve(size);
  w.put_bytes(std::string(kMagic, kMagicSize));
  w.put<std::uint32_t>(Checkpoint::kFormatVersion);
  w.put<std::uint32_t>(c.dimension);
  w.put(c.scene_hash);
  w.put(c.steps);
  w.put(c.time);
  w.put(c.frame);
  w.put(c.substep);
  w.put(c.particles);
  w.put(c.nodes);
  w.put<std::uint32_t>(c.formats.size());
  w.put<std::uint32_t>(c.frame_times.size());
  w.put_bytes(c.formats);
  for (double t : c.frame_times) w.put(t);
  for_each_array(c, [&](const auto& v, std::uint64_t per, std::uint64_t count) {
    if (v.size() != per * count)
      throw CheckpointError(fmt::format("{}: internal error: an array holds {} values, not {}",
                                        target, v.size(), per * count));
    w.put_all(v);
  });
  w.put(checksum(Checkpoint::kFormatVersion, out->data(), out->size()));
}

Checkpoint decode_checkpoint(const std::string& bytes, const std::string& source) {
  const auto fail = [&](const std::string& what) {
    return CheckpointError(source + ": " + what + "; cannot resume");
  };
  const std::size_t size = bytes.size();
  if (bytes.compare(0, kMagicSize, kMagic) != 0) {
    if (size < kMagicSize && bytes == std::string(kMagic, size))
      throw fail(fmt::format("truncated ({} bytes)", size));
    throw fail("not a sablier checkpoint (no SABLIERCKPT signature)");
  }
  ByteReader r(bytes, kMagicSize);
  const auto version = r.get<std::uint32_t>();
  if (!r.ok()) throw fail(fmt::format("truncated ({} bytes)", size));
  if (version < Checkpoint::kOldestReadable || version > Checkpoint::kFormatVersion)
    throw fail(fmt::format(
        "checkpoint format version {}, this sablier ({}) reads versions {} to {}", version,
        SABLIER_VERSION, Checkpoint::kOldestReadable, Checkpoint::kFormatVersion));
  Checkpoint c;
  c.version = version;
  c.dimension = static_cast<int>(r.get<std::uint32_t>());
  c.scene_hash = r.get<std::uint64_t>();
  c.steps = r.get<std::int64_t>();
  c.time = r.get<double>();
  c.frame = r.get<std::int32_t>();
  c.substep = r.get<std::int32_t>();
  c.particles = r.get<std::uint64_t>();
  c.nodes = r.get<std::uint64_t>();
  const auto formats_size = r.get<std::uint32_t>();
  const auto frame_count = r.get<std::uint32_t>();
  if (!r.ok()) throw fail(fmt::format("truncated ({} bytes)", size));
  c.formats.assign(formats_size <= size ? formats_size : 0, ' ');
  c.frame_times.resize(frame_count <= size ? frame_count : 0);

  // The checksum first: every later check may then trust the counts.
  const std::uint64_t expected = formats_size <= size && frame_count <= size
                                     ? expected_size(c, size)
                                     : std::numeric_limits<std::uint64_t>::max();
  ByteReader tail(bytes, size >= 8 ? size - 8 : size);
  const std::uint64_t stored = tail.get<std::uint64_t>();
  if (!tail.ok() || checksum(version, bytes.data(), size - 8) != stored) {
    if (size < expected)
      throw fail(expected == std::numeric_limits<std::uint64_t>::max()
                     ? fmt::format("truncated or corrupted ({} bytes, checksum mismatch)", size)
                     : fmt::format("truncated ({} of {} bytes)", size, expected));
    throw fail("corrupted (checksum mismatch)");
  }
  if (size != expected)
    throw fail(fmt::format("inconsistent ({} bytes, header says {})", size, expected));
  if (c.frame < 0 || c.substep < 0 || c.steps < 0 || frame_count != std::uint32_t(c.frame) + 1)
    throw fail("inconsistent header (frame, substep or step count)");

  for (char& ch : c.formats) ch = static_cast<char>(r.get<std::uint8_t>());
  for (double& t : c.frame_times) t = r.get<double>();
  for_each_array(c, [&](auto& v, std::uint64_t per, std::uint64_t count) {
    v.resize(per * count);
    r.get_all(v);
  });
  return c;
}

}  // namespace sablier
