#pragma once
// Bit-for-bit equality of the results tests compare across thread counts, factorisation paths and
// refinement orders: same shape and the same bytes.
#include <cstring>
#include <vector>

#include <Eigen/Dense>

#include "wefm/core/sys/types.hpp"

namespace wefm::test {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline bool same_bits(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(Complex) * static_cast<size_t>(a.size())) == 0);
}

inline bool same_bits(const VectorXc& a, const VectorXc& b) {
  return a.size() == b.size() && (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(Complex) * static_cast<size_t>(a.size())) == 0);
}

// Same shape, compressed, the same pattern.
inline bool same_pattern(const SpMatC& a, const SpMatC& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() && a.isCompressed() && b.isCompressed() &&
         std::memcmp(a.outerIndexPtr(), b.outerIndexPtr(), sizeof(int) * static_cast<size_t>(a.cols() + 1)) == 0 &&
         (a.nonZeros() == 0 || std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * static_cast<size_t>(a.nonZeros())) == 0);
}

inline bool same_bits(const SpMatC& a, const SpMatC& b) {
  return same_pattern(a, b) &&
         (a.nonZeros() == 0 || std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(Complex) * static_cast<size_t>(a.nonZeros())) == 0);
}

}  // namespace wefm::test
