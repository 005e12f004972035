#include "bipednav/planning/local/interpolated_step.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

namespace bipednav::planning::local {
namespace {

double eval_poly(const Eigen::VectorXd& p, double x) {
  double v = 0.0;
  for (Eigen::Index i = 0; i < p.size(); ++i) v = v * x + p[i];
  return v;
}

}  // namespace

double interpolated_step(const LineSearchSample& s0, const LineSearchSample& prev, const LineSearchSample& cur,
                         double lo, double hi) {
  if (!cur.valid) return std::min(std::max(cur.x * 0.5, lo), hi);
  std::vector<const LineSearchSample*> samples{&s0, &cur};
  if (prev.valid) samples.push_back(&prev);
  const int m = 2 * static_cast<int>(samples.size());
  const int degree = m - 1;
  Eigen::MatrixXd lhs = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd rhs(m);
  int row = 0;
  for (const LineSearchSample* s : samples) {
    for (int j = 0; j <= degree; ++j) lhs(row, j) = std::pow(s->x, degree - j);
    rhs[row++] = s->value;
    for (int j = 0; j < degree; ++j) lhs(row, j) = (degree - j) * std::pow(s->x, degree - j - 1);
    rhs[row++] = s->slope;
  }
  const Eigen::VectorXd poly = lhs.fullPivLu().solve(rhs);
  double best_x = 0.5 * (lo + hi), best = eval_poly(poly, best_x);
  const auto consider = [&](double x) {
    if (!(x >= lo && x <= hi)) return;
    const double v = eval_poly(poly, x);
    if (v < best) best = v, best_x = x;
  };
  consider(lo);
  consider(hi);
  // Critical points: roots of the derivative (real parts, as Ceres takes them).
  Eigen::VectorXd der(degree);
  for (int j = 0; j < degree; ++j) der[j] = (degree - j) * poly[j];
  int lead = 0;
  while (lead < degree - 1 && der[lead] == 0.0) ++lead;
  const int dd = degree - 1 - lead;  // degree of the derivative
  if (dd == 1) {
    consider(-der[lead + 1] / der[lead]);
  } else if (dd >= 2) {
    Eigen::MatrixXd comp = Eigen::MatrixXd::Zero(dd, dd);
    for (int j = 0; j < dd; ++j) comp(0, j) = -der[lead + 1 + j] / der[lead];
    for (int j = 1; j < dd; ++j) comp(j, j - 1) = 1.0;
    if (comp.allFinite()) {
      Eigen::EigenSolver<Eigen::MatrixXd> es(comp, false);
      if (es.info() == Eigen::Success) {
        for (Eigen::Index j = 0; j < es.eigenvalues().size(); ++j) consider(es.eigenvalues()[j].real());
      }
    }
  }
  for (const LineSearchSample* s : samples) consider(s->x);
  return best_x;
}

}  // namespace bipednav::planning::local
