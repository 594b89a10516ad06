// The symmetric-tensor basis of METHOD.md section 4: round trips, trace and
// deviatoric norms, orthonormality for tau:sigma / 2, and the aperture that
// turns the scene's simple-shear friction coefficient into the cone's.
#include <gtest/gtest.h>

#include <random>

#include "core/tensor.hpp"

namespace sablier {
namespace {

template <int D>
Mat<D> random_symmetric(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat<D> a;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) a(i, j) = u(rng);
  return 0.5 * (a + a.transpose());
}

template <int D>
void check_basis() {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 1000; ++trial) {
    const Mat<D> t = random_symmetric<D>(rng);
    const Mat<D> s = random_symmetric<D>(rng);
    const SymVec<D> ct = to_sym<D>(t);
    const SymVec<D> cs = to_sym<D>(s);
    // Round trip.
    EXPECT_LT((from_sym<D>(ct) - t).norm(), 1e-14);
    // Orthonormal for <a, b> = a:b / 2.
    EXPECT_NEAR(ct.dot(cs), 0.5 * (t.array() * s.array()).sum(), 1e-14);
    // Trace coordinate.
    EXPECT_NEAR(trace_of<D>(ct), t.trace(), 1e-14);
    EXPECT_NEAR(ct[0], t.trace() / std::sqrt(2.0 * D), 1e-14);
    // Deviatoric norm |Dev t| = sqrt(Dev t : Dev t / 2).
    const Mat<D> dev = t - t.trace() / D * Mat<D>::Identity();
    EXPECT_NEAR(deviatoric_norm<D>(ct), std::sqrt(0.5 * (dev.array() * dev.array()).sum()), 1e-14);
  }
  // A pure pressure has no deviatoric part.
  const SymVec<D> p = to_sym<D>(Mat<D>::Identity() * 3.0);
  EXPECT_NEAR(deviatoric_norm<D>(p), 0.0, 1e-15);
}

TEST(TensorBasis, RoundTripsAndNorms2D) { check_basis<2>(); }
TEST(TensorBasis, RoundTripsAndNorms3D) { check_basis<3>(); }

// Simple shear at pressure p with shear stress tau: the cone |x_T| <= a x_N
// with a = cone_aperture(mu) admits exactly tau <= mu p (METHOD.md section 4).
template <int D>
void check_simple_shear_friction() {
  const double p = 1000.0, mu = 0.6;
  for (const double ratio : {0.999, 1.001}) {
    Mat<D> s = p * Mat<D>::Identity();
    s(0, 1) = s(1, 0) = ratio * mu * p;
    const SymVec<D> c = to_sym<D>(s);
    const bool inside = deviatoric_norm<D>(c) <= cone_aperture<D>(mu) * c[0];
    EXPECT_EQ(inside, ratio < 1.0) << "ratio " << ratio;
  }
}

TEST(TensorBasis, ApertureIsSimpleShearFriction2D) { check_simple_shear_friction<2>(); }
TEST(TensorBasis, ApertureIsSimpleShearFriction3D) { check_simple_shear_friction<3>(); }

TEST(TensorBasis, CartesianComponents) {
  Mat<3> t;
  t << 1, 4, 5, 4, 2, 6, 5, 6, 3;
  const SymVec<3> c = cartesian_components<3>(to_sym<3>(t));
  const double expect[] = {1, 2, 3, 4, 5, 6};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(c[k], expect[k], 1e-14);
}

}  // namespace
}  // namespace sablier
