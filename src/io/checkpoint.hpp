// checkpoint.bin: the state that, with the resolved scene, determines the
// rest of a run, so that a resumed run is bit-identical to an uninterrupted
// one. Plain arrays (no physics types), little-endian, versioned, with a
// trailing checksum of everything before it (from format 5 zlib's CRC-32 in
// the low 32 bits, before it FNV-1a 64).
//
// Layout: "SABLIERCKPT", u32 format version, u32 dimension, u64 scene hash,
// i64 steps, f64 time, i32 frame, i32 substep, u64 particles, u64 nodes,
// u32 formats length, u32 frame-time count, the formats text, the frame
// times, the particle arrays in the order of the struct, the per-node warm
// start (8-byte values), then from format 4 the per-node cases (one byte
// each), u64 checksum.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/writers.hpp"

namespace sablier {

// A checkpoint that cannot be used; what() is "FILE: what is wrong".
struct CheckpointError : IoError {
  using IoError::IoError;
};

struct Checkpoint {
  // 2: the per-particle material index (several materials per scene).
  // 3: same bytes, but solver.decompaction defaults to "move" since 0.2.0:
  // a run started before would resume with other physics, so it is refused.
  // 4: the per-node cases (warm_case). Format 3 is still read (its run
  // resumes with no cases known, as after a first step, so only the next
  // step's zones can differ from those of an unbroken run).
  // 5: the same layout, the checksum CRC-32 instead of FNV-1a (13 times
  // faster); formats 3 and 4 are still read.
  static constexpr std::uint32_t kFormatVersion = 5;
  static constexpr std::uint32_t kOldestReadable = 3;

  std::uint32_t version = kFormatVersion;  // written: always kFormatVersion

  int dimension = 2;
  std::uint64_t scene_hash = 0;  // fnv1a64 of the resolved scene text
  std::int64_t steps = 0;
  double time = 0.0;
  std::int32_t frame = 0;           // last frame written
  std::int32_t substep = 0;         // steps taken since that frame (fixed substeps count them)
  std::string formats;              // the run's --format, "vtp,csv"
  std::vector<double> frame_times;  // times of frames 0..frame (series.pvd)
  std::uint64_t particles = 0;
  std::uint64_t nodes = 0;  // grid nodes, ghosts included

  // Per particle, interleaved: D, D, D*D, 1, 1, 1, 1, 1, S, 1, 1 values
  // (S = D(D+1)/2), as in core/particles.hpp.
  std::vector<double> position, velocity, affine, volume, cohesion, inertial;
  std::vector<std::int64_t> id;
  std::vector<std::int64_t> material;  // index into the scene's material table
  std::vector<double> stress, phi, shear_rate;
  // Per node, S values: last step's stresses, the next solve's warm start.
  std::vector<double> warm_stress;
  // Per node (format 4; empty when read from format 3): the case its sand
  // row ended the last solve in (DPCase), which the next step's zones use.
  std::vector<std::uint8_t> warm_case;
};

// Throws CheckpointError if the arrays' sizes disagree with the counts.
std::string encode_checkpoint(const Checkpoint& c, const std::string& target);
// The same bytes into `out`, whose storage is reused (a run writes one
// checkpoint per frame).
void encode_checkpoint(const Checkpoint& c, const std::string& target, std::string* out);
// Throws CheckpointError naming `source`: not a checkpoint, another format
// version, truncated, corrupted (checksum), inconsistent.
Checkpoint decode_checkpoint(const std::string& bytes, const std::string& source);

}  // namespace sablier
