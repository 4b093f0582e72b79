#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <array>
#include <complex>
#include <cstdint>
#include <vector>

namespace wefm {

using Index = std::int32_t;  // vertices, triangles, uses: a face holds at most 2^31-1 of each
using Complex = std::complex<double>;
using Vec3 = Eigen::Vector3d;
using Tri = std::array<Index, 3>;
using VectorXc = Eigen::VectorXcd;
using SpMatC = Eigen::SparseMatrix<Complex, Eigen::ColMajor, int>;
using SpMatR = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

constexpr double kPi = 3.14159265358979323846;

}  // namespace wefm
