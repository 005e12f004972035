#pragma once

#include <Eigen/Core>
#include <vector>

namespace bipednav::tracking {

// The linear assignment problem: each row of `cost` (n x m, any shape) to at most one column and
// each column to at most one row. +infinity marks a forbidden pair. Returns, per row, its column
// or -1: an assignment with the most allowed pairs and, among those, the least total cost.
// The Hungarian method (Kuhn 1955, Munkres 1957) in its O(n^2 m) shortest-augmenting-path form
// with dual potentials. Throws Error on a NaN or -infinity entry.
std::vector<int> solve_assignment(const Eigen::MatrixXd& cost);

}  // namespace bipednav::tracking
