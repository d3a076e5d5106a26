#pragma once
// A sparse Cholesky factorisation A = L Lᵀ of a symmetric positive definite matrix whose
// unknowns come in blocks of at most B (a DDA block's unknowns: 6 for a deformable 2D block,
// 3 for a rigid one), computed on B x B dense blocks.
//
// A block system couples all the unknowns of two blocks at once, so its factor's pattern is
// the pattern of the blocks' graph. Eigen's simplicial factorisations work unknown by unknown
// and spend their time on index arithmetic; here every operation is a fixed-size B x B
// product (B³ flops per index lookup), and the ordering (approximate minimum degree, Eigen's)
// and the symbolic analysis run on the graph of the blocks, B² times smaller. On the
// pre-solve's stiffness of a 333 x 30 joint-cut mass (59 940 unknowns), ordering and
// factorisation take 0.13 s against 0.50 s for Eigen's SimplicialLDLT, and a solve 0.010 s
// against 0.019 s (docs/performance.md).
//
// The method is the up-looking one (T. Davis, "Direct Methods for Sparse Linear Systems", ch. 4:
// row k of L from a sparse triangular solve along the elimination tree) with blocks for
// scalars: for each block row k,
//   Y_j = A_jk - Σ_{m<j} L_jm X_m,   X_j = L_jj⁻¹ Y_j,   L_kj = X_jᵀ   (j in row k's pattern)
//   L_kk = chol(A_kk - Σ_j X_jᵀ X_j),
// L_kk⁻¹ kept, so that every step is a B x B product.
// A block with fewer than B unknowns is padded with identity rows, which decouple. The 2D
// pre-solve assembles its system block by block (Term), so no scalar sparse matrix is built.

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace rockcontact::dynamics {

template <int B>
class BlockCholesky {
 public:
  using Block = Eigen::Matrix<double, B, B>;
  using Segment = Eigen::Matrix<double, B, 1>;

  // A term of A: `value` is added to the block of A in block row `row`, block column `col`
  // (and its transpose to the block at (col, row): a coupling is given once). Terms at the
  // same place add up. Only a block's first sizes[i] rows and columns are read.
  struct Term {
    int row = 0, col = 0;
    Block value;
  };

  // Factorises the matrix of `terms` over blocks of sizes[i] unknowns (1 to B; block i's
  // unknowns follow block i - 1's). Returns false when a pivot block is not positive definite
  // (A is not SPD to rounding); solve is then not to be called. The ordering and the symbolic
  // analysis are kept for the next call with the same sizes and the same (row, col) sequence
  // of terms (an open-close iteration's solves, whose springs change but not which blocks
  // they couple), and so is the storage.
  bool factorize(std::span<const int> sizes, std::span<const Term> terms);

  // Solves A x = b, after factorize returned true.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

  // Blocks of L below the diagonal (the pattern with the ordering's fill).
  std::size_t factor_blocks() const { return rows_.size(); }

 private:
  bool analyzed_for(std::span<const int> sizes, std::span<const Term> terms) const;
  void analyze(std::span<const int> sizes, std::span<const Term> terms);
  void load(std::span<const Term> terms);

  std::vector<int> sizes_;
  std::vector<std::pair<int, int>> pattern_;  // the terms' places the analysis was made for
  std::vector<int> term_at_;                  // where each term goes in a_value_ (< 0: transposed, ~p)
  std::vector<Eigen::Index> starts_;  // block i's first unknown
  std::vector<int> order_, place_;    // order_[new] = old block, place_[old] = new
  std::vector<int> parent_;           // elimination tree (new numbering), -1 at a root
  // A's upper triangle by block columns (new numbering), rows increasing, the diagonal last.
  std::vector<int> a_start_, a_row_;
  std::vector<Block> a_value_;
  // L below the diagonal by block columns, rows in increasing order; the inverses of its
  // diagonal blocks (lower triangular), so that each solve with one is a product.
  std::vector<int> l_start_, rows_;
  std::vector<Block> values_, inverse_diagonal_;
  // The factorisation's scratch: a dense block column, the row pattern, how far each column
  // of L is filled.
  std::vector<Block> y_;
  std::vector<int> mark_, row_pattern_, filled_;
};

extern template class BlockCholesky<6>;

}  // namespace rockcontact::dynamics
