#include "bipednav/planning/local/band_cholesky.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "bipednav/common/rng.hpp"

namespace bipednav::planning::local {
namespace {

constexpr int kB = 3;
constexpr std::size_t kW = kB + 1;

// A random symmetric positive definite matrix with half-bandwidth kB, rows 4-6 with an empty
// left part of the band (the envelope band_cholesky skips), in dense and in band storage.
void random_band_matrix(std::size_t n, Eigen::MatrixXd& dense, std::vector<double>& band) {
  Rng rng(11);
  dense = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 1; d <= std::min<std::size_t>(kB, i); ++d) {
      const bool empty = i >= 4 && i <= 6 && d >= 2;
      const double v = empty ? 0.0 : rng.uniform(-1.0, 1.0);
      dense(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i - d)) = v;
      dense(static_cast<Eigen::Index>(i - d), static_cast<Eigen::Index>(i)) = v;
    }
  for (std::size_t i = 0; i < n; ++i) dense(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = 8.0;
  band.assign(n * kW, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d <= std::min<std::size_t>(kB, i); ++d)
      band[i * kW + d] = dense(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i - d));
}

TEST(BandCholesky, SolvesLikeTheDenseCholesky) {
  const std::size_t n = 12;
  Eigen::MatrixXd dense;
  std::vector<double> band;
  random_band_matrix(n, dense, band);
  std::vector<std::size_t> first;
  ASSERT_TRUE(band_cholesky<kB>(band, n, first));
  EXPECT_EQ(first[5], 4u);  // row 5 starts at its first non-zero, one left of the diagonal
  EXPECT_EQ(first[9], 6u);  // a full row: the whole band
  const Eigen::MatrixXd L = dense.llt().matrixL();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d <= std::min<std::size_t>(kB, i); ++d)
      EXPECT_NEAR(band[i * kW + d], L(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i - d)), 1e-12);
  Eigen::VectorXd b(static_cast<Eigen::Index>(n));
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) b[static_cast<Eigen::Index>(i)] = y[i] = std::sin(1.0 + i);
  band_solve<kB>(band, n, y);
  const Eigen::VectorXd x = dense.llt().solve(b);
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(y[i], x[static_cast<Eigen::Index>(i)], 1e-12);
}

TEST(BandCholesky, RejectsAMatrixThatIsNotPositiveDefinite) {
  const std::size_t n = 6;
  Eigen::MatrixXd dense;
  std::vector<double> band;
  random_band_matrix(n, dense, band);
  band[3 * kW] = -1.0;  // a negative diagonal entry
  std::vector<std::size_t> first;
  EXPECT_FALSE(band_cholesky<kB>(band, n, first));
  random_band_matrix(n, dense, band);
  band[2 * kW] = std::nan("");
  EXPECT_FALSE(band_cholesky<kB>(band, n, first));
}

}  // namespace
}  // namespace bipednav::planning::local
