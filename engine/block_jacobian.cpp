// SPDX-License-Identifier: BSD-3-Clause
#include "engine/block_jacobian.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace igac {
namespace {
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
}  // namespace

Eigen::SparseMatrix<double> assemble_condensed(const BlockJacobian& J) {
  const int n = int(J.K.rows()), m = int(J.B.rows());
  if (m == 0 && J.K_coupling.nonZeros() == 0) {  // K is the whole matrix (a general J, friction's iterations)
    Eigen::SparseMatrix<double> A = J.K;
    A.makeCompressed();
    return A;
  }
  Eigen::SparseMatrix<double> A(condensed_rows(J, 0, n + m));  // (every row: the one walk of J's blocks)
  A.makeCompressed();
  return A;
}

RowSparse condensed_rows(const BlockJacobian& J, int begin, int end, int columns, const RowSparse* extra) {
  const int n = int(J.K.rows()), m = int(J.B.rows()), rows = end - begin;
  if (columns < 0) columns = n + m;
  const auto mine = [&](int row) { return row >= begin && row < end; };
  // every entry (row, col, value) of the condensed J (and `extra`) in the rows and columns asked for
  const auto for_each_entry = [&](auto&& take) {
    for (const Eigen::SparseMatrix<double>* A : {&J.K, &J.K_coupling})
      for (int c = 0; c < std::min(int(A->outerSize()), columns); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(*A, c); it; ++it)
          if (mine(int(it.row()))) take(int(it.row()), c, it.value());
    for (int k = 0; k < m; ++k) {
      const int row = n + k;
      for (RowSparse::InnerIterator it(J.B, k); it; ++it) {
        if (mine(int(it.col())) && row < columns) take(int(it.col()), row, it.value());
        if (mine(row)) take(row, int(it.col()), J.s[k] * it.value());
      }
      if (mine(row) && row < columns) take(row, row, J.d[k]);
    }
    if (J.has_mixed_rows())
      for (int k = std::max(begin - n, 0); k < std::min(end - n, m); ++k) {
        const int row = n + k;
        if (J.mixed_B.rows() > 0)
          for (RowSparse::InnerIterator j(J.mixed_B, k); j; ++j)
            for (RowSparse::InnerIterator it(J.B, int(j.col())); it; ++it)
              if (it.col() < columns) take(row, int(it.col()), j.value() * it.value());
        if (J.mixed_lambda.rows() > 0)
          for (RowSparse::InnerIterator j(J.mixed_lambda, k); j; ++j)
            if (n + j.col() < columns) take(row, n + int(j.col()), j.value());
      }
    if (extra)
      for (int r = std::max(begin, 0); r < std::min(end, int(extra->rows())); ++r)
        for (RowSparse::InnerIterator it(*extra, r); it; ++it)
          if (it.col() < columns) take(r, int(it.col()), it.value());
  };
  // two passes into the result's own arrays (counted, then placed), then
  // each row sorted and its repeated columns summed in place
  std::vector<int> start(size_t(rows) + 1, 0);
  for_each_entry([&](int row, int, double) { ++start[size_t(row - begin) + 1]; });
  for (int r = 0; r < rows; ++r) start[size_t(r) + 1] += start[size_t(r)];
  RowSparse R(rows, columns);
  R.resizeNonZeros(start.back());
  std::vector<int> next(start.begin(), start.end() - 1);
  int* col = R.innerIndexPtr();
  double* val = R.valuePtr();
  for_each_entry([&](int row, int c, double v) {
    const int at = next[size_t(row - begin)]++;
    col[at] = c;
    val[at] = v;
  });
  std::vector<std::pair<int, double>> row_entries;
  int kept = 0;
  int* outer = R.outerIndexPtr();
  for (int r = 0; r < rows; ++r) {
    row_entries.clear();
    for (int k = start[size_t(r)]; k < start[size_t(r) + 1]; ++k) row_entries.emplace_back(col[k], val[k]);
    std::stable_sort(row_entries.begin(), row_entries.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    outer[r] = kept;
    for (size_t k = 0; k < row_entries.size(); ++k) {
      if (k > 0 && row_entries[k].first == row_entries[k - 1].first) {
        val[kept - 1] += row_entries[k].second;
      } else {
        col[kept] = row_entries[k].first;
        val[kept++] = row_entries[k].second;
      }
    }
  }
  outer[rows] = kept;
  R.resizeNonZeros(kept);
  return R;
}

bool BlockJacobian::closed_row(int k) const {
  if (s[k] != 0.0) return true;
  const auto holds = [k](const Eigen::SparseMatrix<double, Eigen::RowMajor>& M) {
    return M.rows() > k && bool(Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator(M, k));
  };
  return holds(mixed_B) || holds(mixed_lambda);
}

BlockJacobian as_one_block(const BlockJacobian& J) {
  BlockJacobian one;
  one.K = assemble_condensed(J);
  one.general = true;
  one.B.resize(0, one.K.cols());
  one.rigid_modes = J.rigid_modes;
  one.pinned = J.pinned;
  one.local = J.local;
  return one;
}

Eigen::SparseMatrix<double> assemble_full(const BlockJacobian& J) {
  Eigen::SparseMatrix<double> A = assemble_condensed(J);
  const BlockJacobian::Local& L = J.local;
  if (L.size() == 0) return A;
  const int nr = int(A.rows()), nz = L.size();
  // the displacement block without the condensed C^T diag(g) C, and the local rows and columns
  const Eigen::SparseMatrix<double> CtgC =
      Eigen::SparseMatrix<double>(L.C.transpose()) * L.g.asDiagonal() * Eigen::SparseMatrix<double>(L.C);
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  for (int c = 0; c < CtgC.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(CtgC, c); it; ++it) t.emplace_back(it.row(), it.col(), -it.value());
  for (int e = 0; e < nz; ++e) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L.C, e); it; ++it) {
      t.emplace_back(int(it.col()), nr + e, L.g[e] * it.value());
      t.emplace_back(nr + e, int(it.col()), L.h[e] * it.value());
    }
    t.emplace_back(nr + e, nr + e, -L.h[e]);
  }
  Eigen::SparseMatrix<double> F(nr + nz, nr + nz);
  F.setFromTriplets(t.begin(), t.end());
  F.makeCompressed();
  return F;
}

CondensedRhs condense_rhs(const BlockJacobian& J, const Eigen::VectorXd& b_whole) {
  const BlockJacobian::Local& L = J.local;
  const int nz = L.size(), nr = int(b_whole.size()) - nz;
  CondensedRhs c{b_whole.head(nr), {}};
  if (nz > 0) {
    c.bz_h = b_whole.tail(nz).cwiseQuotient(L.h);
    c.b.head(L.C.cols()).noalias() += L.C.transpose() * L.g.cwiseProduct(c.bz_h);
  }
  return c;
}

void recover_local(const BlockJacobian& J, const CondensedRhs& rhs, Eigen::VectorXd& x) {
  const BlockJacobian::Local& L = J.local;
  const int nz = L.size();
  if (nz == 0) return;
  const int nr = int(x.size());
  x.conservativeResize(nr + nz);
  x.tail(nz).noalias() = L.C * x.head(L.C.cols()) - rhs.bz_h;
}

}  // namespace igac
