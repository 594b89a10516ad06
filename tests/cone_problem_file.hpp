// A cone problem as the solver receives it, saved to a file and read back:
// tests solve a recorded hard step again without replaying the simulation
// that led to it, which any change of the engine would steer elsewhere.
// Sand rows only (no obstacle contact rows, no rigid bodies). What
// assemble_delassus derives (the blocks, inverse volumes, packed couplings)
// is rebuilt on reading; the velocity unknowns are stored where they or
// their inverse masses are non-zero. Little-endian (io/bytes.hpp), written
// atomically (io/writers.hpp).
#pragma once

#include <limits>
#include <stdexcept>
#include <string>

#include "io/bytes.hpp"
#include "io/writers.hpp"
#include "solver/cone_problem.hpp"

namespace sablier::test {

inline constexpr char kConeProblemMagic[] = "sablier-cone-problem 1\n";

template <int D>
void save_cone_problem(const ConeProblem<D>& p, const std::string& path) {
  if (p.first_contact < p.rows())
    throw std::invalid_argument("save_cone_problem: contact rows are not stored");
  ByteWriter w;
  w.put_bytes(kConeProblemMagic);
  w.put(std::int32_t(D));
  w.put(std::int64_t(p.velocity.size()));
  std::int64_t used = 0;
  for (std::size_t i = 0; i < p.velocity.size(); ++i)
    used += !(p.velocity[i].isZero() && p.inv_mass[i].isZero());
  w.put(used);
  for (std::size_t i = 0; i < p.velocity.size(); ++i) {
    if (p.velocity[i].isZero() && p.inv_mass[i].isZero()) continue;
    w.put(std::int64_t(i));
    for (int c = 0; c < D; ++c) w.put(p.velocity[i][c]);
    for (int c = 0; c < D; ++c) w.put(p.inv_mass[i][c]);
  }
  for (const std::int64_t s : p.stencil) w.put(s);
  w.put(std::int32_t(p.zones));
  w.put(std::int64_t(p.colour_start.size()));
  for (const int c : p.colour_start) w.put(std::int32_t(c));
  w.put(std::int64_t(p.rows()));
  for (int j = 0; j < p.rows(); ++j) {
    w.put(p.node[j]);
    for (int s = 0; s < ConeProblem<D>::NS; ++s)
      for (int c = 0; c < D; ++c) w.put(p.coupling[j](c, s));
    w.put(p.volume[j]);
    w.put(p.k[j]);
    w.put(p.aperture[j]);
    w.put(p.cohesion[j]);
    for (int c = 0; c < sym_size(D); ++c) w.put(p.lambda[j][c]);
  }
  write_file_atomic(path, w.data());
}

template <int D>
ConeProblem<D> load_cone_problem(const std::string& path) {
  const std::string data = read_file(path);
  const std::string magic = kConeProblemMagic;
  if (data.compare(0, magic.size(), magic) != 0)
    throw std::runtime_error(path + ": not a cone problem file");
  ByteReader r(data, magic.size());
  if (r.get<std::int32_t>() != D) throw std::runtime_error(path + ": another dimension");
  ConeProblem<D> p;
  const std::int64_t nodes = r.get<std::int64_t>();
  if (!r.ok() || nodes < 0 || nodes > std::int64_t(1) << 32)
    throw std::runtime_error(path + ": truncated");
  p.velocity.assign(nodes, Vec<D>::Zero());
  p.inv_mass.assign(nodes, Vec<D>::Zero());
  const std::int64_t used = r.get<std::int64_t>();
  for (std::int64_t k = 0; k < used && r.ok(); ++k) {
    const std::int64_t i = r.get<std::int64_t>();
    if (i < 0 || i >= nodes) throw std::runtime_error(path + ": node out of range");
    for (int c = 0; c < D; ++c) p.velocity[i][c] = r.get<double>();
    for (int c = 0; c < D; ++c) p.inv_mass[i][c] = r.get<double>();
  }
  for (std::int64_t& s : p.stencil) s = r.get<std::int64_t>();
  p.zones = r.get<std::int32_t>();
  const std::int64_t colours = r.get<std::int64_t>();
  if (!r.ok() || colours < 0 || colours > 1 << 20) throw std::runtime_error(path + ": truncated");
  p.colour_start.resize(colours);
  for (int& c : p.colour_start) c = r.get<std::int32_t>();
  const std::int64_t rows = r.get<std::int64_t>();
  if (!r.ok() || rows < 0 || rows > std::numeric_limits<int>::max())
    throw std::runtime_error(path + ": truncated");
  p.resize_rows(static_cast<int>(rows));
  for (int j = 0; j < p.rows(); ++j) {
    p.node[j] = r.get<std::int64_t>();
    for (int s = 0; s < ConeProblem<D>::NS; ++s)
      for (int c = 0; c < D; ++c) p.coupling[j](c, s) = r.get<double>();
    p.volume[j] = r.get<double>();
    p.k[j] = r.get<double>();
    p.aperture[j] = r.get<double>();
    p.cohesion[j] = r.get<double>();
    for (int c = 0; c < sym_size(D); ++c) p.lambda[j][c] = r.get<double>();
  }
  if (!r.ok()) throw std::runtime_error(path + ": truncated");
  assemble_delassus(p);
  return p;
}

}  // namespace sablier::test
