#pragma once
// Small fixed-size Eigen types of the 2D frame and the insertion callback used by assembly.
//
// Dof numbering: every node carries (ux, uy, rz); global dof of node n, component k is
// 3*n + k. An element's local vector is (uxi, uyi, rzi, uxj, uyj, rzj).
#include <Eigen/Core>
#include <functional>

namespace pfem::structure {

using Vec2 = Eigen::Matrix<double, 2, 1>;
using Vec3 = Eigen::Matrix<double, 3, 1>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat2 = Eigen::Matrix<double, 2, 2>;
using Mat3 = Eigen::Matrix<double, 3, 3>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat36 = Eigen::Matrix<double, 3, 6>;

inline constexpr int kDofsPerNode = 3;

// Receives one matrix entry (global row, global column, value); entries with the same
// (row, col) are to be summed. Assembly never cares which sparse backend is behind it.
using AddEntry = std::function<void(int row, int col, double value)>;

}  // namespace pfem::structure
