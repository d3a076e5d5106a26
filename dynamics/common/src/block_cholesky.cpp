#include "block_cholesky.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

namespace rockcontact::dynamics {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

}  // namespace

template <int B>
bool BlockCholesky<B>::factorize(std::span<const int> sizes, std::span<const Term> terms) {
  if (!analyzed_for(sizes, terms)) analyze(sizes, terms);
  load(terms);
  const int n = static_cast<int>(sizes_.size());
  std::fill(mark_.begin(), mark_.end(), -1);
  std::fill(filled_.begin(), filled_.end(), 0);
  for (int k = 0; k < n; ++k) {
    // Row k's pattern: the elimination tree's paths from A's blocks in column k up to k, in an
    // order where each block comes after every block below it on its path.
    int top = n;
    mark_[at(k)] = k;
    const int last = a_start_[at(k) + 1] - 1;  // the diagonal block
    Block pivot = a_value_[at(last)];
    for (int p = a_start_[at(k)]; p < last; ++p) {
      int i = a_row_[at(p)];
      y_[at(i)] = a_value_[at(p)];
      int length = 0;
      for (; mark_[at(i)] != k; i = parent_[at(i)]) {
        row_pattern_[at(length++)] = i;
        mark_[at(i)] = k;
      }
      while (length > 0) row_pattern_[at(--top)] = row_pattern_[at(--length)];
    }
    for (; top < n; ++top) {
      const std::size_t j = at(row_pattern_[at(top)]);
      const Block x = inverse_diagonal_[j] * y_[j];
      y_[j].setZero();
      const std::size_t begin = at(l_start_[j]), end = begin + at(filled_[j]);
      for (std::size_t p = begin; p < end; ++p) y_[at(rows_[p])].noalias() -= values_[p] * x;
      pivot.noalias() -= x.transpose() * x;
      rows_[end] = k;
      values_[end] = x.transpose();
      ++filled_[j];
    }
    const Eigen::LLT<Block> llt(pivot);
    if (llt.info() != Eigen::Success) return false;
    inverse_diagonal_[at(k)] = llt.matrixL().solve(Block::Identity());
  }
  return true;
}

template <int B>
bool BlockCholesky<B>::analyzed_for(std::span<const int> sizes, std::span<const Term> terms) const {
  return std::equal(sizes.begin(), sizes.end(), sizes_.begin(), sizes_.end()) &&
         std::equal(terms.begin(), terms.end(), pattern_.begin(), pattern_.end(),
                    [](const Term& t, const std::pair<int, int>& p) { return t.row == p.first && t.col == p.second; });
}

// The blocks' graph, its ordering, the elimination tree and the factor's column counts.
template <int B>
void BlockCholesky<B>::analyze(std::span<const int> sizes, std::span<const Term> terms) {
  const std::size_t n = sizes.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (sizes[i] < 1 || sizes[i] > B) {
      throw std::invalid_argument("BlockCholesky: block " + std::to_string(i) + " has " + std::to_string(sizes[i]) +
                                  " unknowns, not 1 to " + std::to_string(B));
    }
  }
  for (const Term& t : terms) {
    if (t.row < 0 || at(t.row) >= n || t.col < 0 || at(t.col) >= n) {
      throw std::invalid_argument("BlockCholesky: a term at block (" + std::to_string(t.row) + ", " +
                                  std::to_string(t.col) + ") is outside the " + std::to_string(n) + " blocks");
    }
  }
  sizes_.assign(sizes.begin(), sizes.end());
  starts_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) starts_[i + 1] = starts_[i] + sizes_[i];
  pattern_.clear();
  for (const Term& t : terms) pattern_.emplace_back(t.row, t.col);
  std::vector<Eigen::Triplet<double>> graph;
  graph.reserve(n + terms.size());
  for (std::size_t j = 0; j < n; ++j) graph.emplace_back(static_cast<int>(j), static_cast<int>(j), 1.0);
  for (const Term& t : terms) {
    if (t.row != t.col) graph.emplace_back(t.row, t.col, 1.0);
  }
  Eigen::SparseMatrix<double> pattern(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  pattern.setFromTriplets(graph.begin(), graph.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation;
  Eigen::AMDOrdering<int>()(pattern, permutation);  // orders the pattern of A + Aᵀ
  order_.assign(permutation.indices().data(), permutation.indices().data() + n);
  place_.resize(n);
  for (std::size_t k = 0; k < n; ++k) place_[at(order_[k])] = static_cast<int>(k);
  // A's upper triangle in the new numbering, by columns; the diagonal block last.
  std::vector<std::vector<int>> above(n);
  for (const Term& t : terms) {
    const int r = place_[at(t.row)], c = place_[at(t.col)];
    if (r != c) above[at(std::max(r, c))].push_back(std::min(r, c));
  }
  a_start_.assign(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    std::sort(above[k].begin(), above[k].end());
    above[k].erase(std::unique(above[k].begin(), above[k].end()), above[k].end());
    a_start_[k + 1] = a_start_[k] + static_cast<int>(above[k].size()) + 1;
  }
  a_row_.resize(at(a_start_[n]));
  a_value_.resize(a_row_.size());
  for (std::size_t k = 0; k < n; ++k) {
    std::copy(above[k].begin(), above[k].end(), a_row_.begin() + a_start_[k]);
    a_row_[at(a_start_[k + 1] - 1)] = static_cast<int>(k);
  }
  // The elimination tree and how many blocks each column of L has below its diagonal.
  parent_.assign(n, -1);
  std::vector<int> mark(n, -1), count(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const int row = static_cast<int>(k);
    mark[k] = row;
    for (int p = a_start_[k]; p < a_start_[k + 1] - 1; ++p) {
      for (int i = a_row_[at(p)]; mark[at(i)] != row; i = parent_[at(i)]) {
        if (parent_[at(i)] == -1) parent_[at(i)] = row;
        ++count[at(i)];
        mark[at(i)] = row;
      }
    }
  }
  l_start_.assign(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) l_start_[k + 1] = l_start_[k] + count[k];
  rows_.resize(at(l_start_[n]));
  values_.resize(rows_.size());
  inverse_diagonal_.resize(n);
  y_.assign(n, Block::Zero());
  mark_.resize(n);
  row_pattern_.resize(n);
  filled_.resize(n);
  // Where each term goes: its block of A's upper triangle, transposed if it lies below.
  term_at_.clear();
  for (const Term& t : terms) {
    const int r = place_[at(t.row)], c = place_[at(t.col)];
    const int row = std::min(r, c), col = std::max(r, c);
    const auto first = a_row_.begin() + a_start_[at(col)], last = a_row_.begin() + a_start_[at(col) + 1];
    const int p = static_cast<int>(std::lower_bound(first, last, row) - a_row_.begin());
    term_at_.push_back(r <= c ? p : ~p);
  }
}

// The terms into A's upper blocks, each cut to its blocks' sizes; a block's padding (past its
// unknowns) is the identity.
template <int B>
void BlockCholesky<B>::load(std::span<const Term> terms) {
  std::fill(a_value_.begin(), a_value_.end(), Block::Zero());
  for (std::size_t k = 0; k < terms.size(); ++k) {
    const Term& t = terms[k];
    const int rows = sizes_[at(t.row)], cols = sizes_[at(t.col)];
    if (term_at_[k] >= 0) {
      a_value_[at(term_at_[k])].topLeftCorner(rows, cols) += t.value.topLeftCorner(rows, cols);
    } else {
      a_value_[at(~term_at_[k])].topLeftCorner(cols, rows) += t.value.topLeftCorner(rows, cols).transpose();
    }
  }
  for (std::size_t old = 0; old < sizes_.size(); ++old) {
    const std::size_t k = at(place_[old]);
    Block& diagonal = a_value_[at(a_start_[k + 1] - 1)];
    for (int d = sizes_[old]; d < B; ++d) diagonal(d, d) = 1.0;
  }
}

template <int B>
Eigen::VectorXd BlockCholesky<B>::solve(const Eigen::VectorXd& b) const {
  const std::size_t n = order_.size();
  std::vector<Segment> x(n, Segment::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t old = at(order_[k]);
    x[k].head(sizes_[old]) = b.segment(starts_[old], sizes_[old]);
  }
  for (std::size_t j = 0; j < n; ++j) {  // L z = b, by columns
    x[j] = inverse_diagonal_[j] * x[j];
    for (int p = l_start_[j]; p < l_start_[j + 1]; ++p) x[at(rows_[at(p)])].noalias() -= values_[at(p)] * x[j];
  }
  for (std::size_t j = n; j-- > 0;) {  // Lᵀ x = z
    for (int p = l_start_[j]; p < l_start_[j + 1]; ++p) {
      x[j].noalias() -= values_[at(p)].transpose() * x[at(rows_[at(p)])];
    }
    x[j] = inverse_diagonal_[j].transpose() * x[j];
  }
  Eigen::VectorXd out(b.size());
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t old = at(order_[k]);
    out.segment(starts_[old], sizes_[old]) = x[k].head(sizes_[old]);
  }
  return out;
}

template class BlockCholesky<6>;

}  // namespace rockcontact::dynamics
