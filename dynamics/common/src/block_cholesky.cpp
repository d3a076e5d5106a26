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
  sizes_.assign(sizes.begin(), sizes.end());
  starts_.assign(sizes_.size() + 1, 0);
  for (std::size_t i = 0; i < sizes_.size(); ++i) {
    if (sizes_[i] < 1 || sizes_[i] > B) {
      throw std::invalid_argument("BlockCholesky: block " + std::to_string(i) + " has " + std::to_string(sizes_[i]) +
                                  " unknowns, not 1 to " + std::to_string(B));
    }
    starts_[i + 1] = starts_[i] + sizes_[i];
  }
  const int n = static_cast<int>(sizes_.size());
  for (const Term& t : terms) {
    if (t.row < 0 || t.row >= n || t.col < 0 || t.col >= n) {
      throw std::invalid_argument("BlockCholesky: a term at block (" + std::to_string(t.row) + ", " +
                                  std::to_string(t.col) + ") is outside the " + std::to_string(n) + " blocks");
    }
  }
  analyze(terms);
  load(terms);
  std::vector<Block> y(at(n), Block::Zero());
  std::vector<int> mark(at(n), -1), pattern(at(n)), filled(at(n), 0);
  for (int k = 0; k < n; ++k) {
    // Row k's pattern: the elimination tree's paths from A's blocks in column k up to k, in an
    // order where each block comes after every block below it on its path.
    int top = n;
    mark[at(k)] = k;
    const int last = a_start_[at(k) + 1] - 1;  // the diagonal block
    Block pivot = a_value_[at(last)];
    for (int p = a_start_[at(k)]; p < last; ++p) {
      int i = a_row_[at(p)];
      y[at(i)] = a_value_[at(p)];
      int length = 0;
      for (; mark[at(i)] != k; i = parent_[at(i)]) {
        pattern[at(length++)] = i;
        mark[at(i)] = k;
      }
      while (length > 0) pattern[at(--top)] = pattern[at(--length)];
    }
    for (; top < n; ++top) {
      const std::size_t j = at(pattern[at(top)]);
      const Block x = inverse_diagonal_[j] * y[j];
      y[j].setZero();
      const std::size_t begin = at(l_start_[j]), end = begin + at(filled[j]);
      for (std::size_t p = begin; p < end; ++p) y[at(rows_[p])].noalias() -= values_[p] * x;
      pivot.noalias() -= x.transpose() * x;
      rows_[end] = k;
      values_[end] = x.transpose();
      ++filled[j];
    }
    const Eigen::LLT<Block> llt(pivot);
    if (llt.info() != Eigen::Success) return false;
    inverse_diagonal_[at(k)] = llt.matrixL().solve(Block::Identity());
  }
  return true;
}

// The blocks' graph, its ordering, the elimination tree and the factor's column counts.
template <int B>
void BlockCholesky<B>::analyze(std::span<const Term> terms) {
  const std::size_t n = sizes_.size();
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
}

template <int B>
std::size_t BlockCholesky<B>::place_of(int row, int col) const {
  const auto first = a_row_.begin() + a_start_[at(col)], last = a_row_.begin() + a_start_[at(col) + 1];
  return static_cast<std::size_t>(std::lower_bound(first, last, row) - a_row_.begin());
}

// The terms into A's upper blocks, each cut to its blocks' sizes; a block's padding (past its
// unknowns) is the identity.
template <int B>
void BlockCholesky<B>::load(std::span<const Term> terms) {
  a_value_.assign(a_row_.size(), Block::Zero());
  for (const Term& t : terms) {
    const int r = place_[at(t.row)], c = place_[at(t.col)];
    const auto value = t.value.topLeftCorner(sizes_[at(t.row)], sizes_[at(t.col)]);
    if (r <= c) {
      a_value_[place_of(r, c)].topLeftCorner(sizes_[at(t.row)], sizes_[at(t.col)]) += value;
    } else {
      a_value_[place_of(c, r)].topLeftCorner(sizes_[at(t.col)], sizes_[at(t.row)]) += value.transpose();
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
