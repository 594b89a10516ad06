// FNV-1a, 64 bits: a small, dependency-free hash for identifying a run's
// scene (run.json, checkpoint.bin) and checking a checkpoint's integrity. It
// detects accidental corruption, not tampering.
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace sablier {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;

inline std::uint64_t fnv1a64(const char* data, std::size_t n, std::uint64_t h = kFnvOffset) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

inline std::uint64_t fnv1a64(const std::string& s) { return fnv1a64(s.data(), s.size()); }

// 16 lower-case hex digits.
inline std::string hash_hex(std::uint64_t h) { return fmt::format("{:016x}", h); }

}  // namespace sablier
