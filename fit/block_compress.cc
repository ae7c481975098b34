#include "fit/block_compress.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace brdfit::internal {

namespace {

// One Gram entry: sum over the chunk's rows of a[r] b[r], in four partial sums (the header's
// order). Portable: any CPU; on x86-64 compiled without FMA, so its bits are the AVX loop's.
double ColumnDot(const double* a, const double* b) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  for (int r = 0; r < kGramChunk; r += 4) {
    s0 += a[r] * b[r];
    s1 += a[r + 1] * b[r + 1];
    s2 += a[r + 2] * b[r + 2];
    s3 += a[r + 3] * b[r + 3];
  }
  return (s0 + s1) + (s2 + s3);
}

}  // namespace

void AccumulateGramColumnsPortable(const double* columns, int cols, double* gram) {
  for (int j = 0; j < cols; ++j) {
    for (int i = j; i < cols; ++i) {
      gram[i + j * cols] += ColumnDot(columns + i * kGramChunk, columns + j * kGramChunk);
    }
  }
}

namespace {

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// The four partial sums as the four lanes of one AVX register (separate multiply and add).
__attribute__((target("avx"))) void GramColumnsAvx(const double* columns, int cols, double* gram) {
  for (int j = 0; j < cols; ++j) {
    const double* b = columns + j * kGramChunk;
    for (int i = j; i < cols; ++i) {
      const double* a = columns + i * kGramChunk;
      __m256d s = _mm256_setzero_pd();
      for (int r = 0; r < kGramChunk; r += 4) {
        s = _mm256_add_pd(s, _mm256_mul_pd(_mm256_loadu_pd(a + r), _mm256_loadu_pd(b + r)));
      }
      alignas(32) double l[4];
      _mm256_store_pd(l, s);
      gram[i + j * cols] += (l[0] + l[1]) + (l[2] + l[3]);
    }
  }
}

bool HaveAvx() {
  static const bool have = __builtin_cpu_supports("avx");
  return have;
}
#endif

}  // namespace

void AccumulateGramColumns(const double* columns, int cols, double* gram) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  if (HaveAvx()) return GramColumnsAvx(columns, cols, gram);
#endif
  AccumulateGramColumnsPortable(columns, cols, gram);
}

bool CompressGram(const double* gram, int P, double cost, double* residuals, double* jacobian) {
  const Eigen::Map<const Eigen::MatrixXd> g(gram, P + 1, P + 1);
  const Eigen::MatrixXd full = g.selfadjointView<Eigen::Lower>();
  if (!full.allFinite() || !std::isfinite(cost)) return false;
  const Eigen::MatrixXd jtj = full.topLeftCorner(P, P);
  const Eigen::VectorXd jtr = full.topRightCorner(P, 1);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jtj);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::MatrixXd& v = eig.eigenvectors();
  // Directions with eigenvalues below this carry no gradient (J^T r lies in range(J^T J)).
  const double cut = 1e-14 * std::max(lambda.maxCoeff(), 0.0);
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> jac(jacobian,
                                                                                         P + 1, P);
  double z2 = 0;
  for (int k = 0; k < P; ++k) {
    if (lambda[k] > cut && lambda[k] > 0) {
      const double sl = std::sqrt(lambda[k]);
      jac.row(k) = sl * v.col(k).transpose();
      residuals[k] = v.col(k).dot(jtr) / sl;
    } else {
      jac.row(k).setZero();
      residuals[k] = 0.0;
    }
    z2 += residuals[k] * residuals[k];
  }
  jac.row(P).setZero();
  if (z2 > cost) {
    // Only through rounding (|z|^2 <= r^T r exactly): keep the cost exact.
    const double f = z2 > 0 ? std::sqrt(cost / z2) : 0.0;
    for (int k = 0; k < P; ++k) residuals[k] *= f;
    z2 = cost;
  }
  residuals[P] = std::sqrt(cost - z2);
  return jac.allFinite() && std::isfinite(residuals[P]);
}

}  // namespace brdfit::internal
