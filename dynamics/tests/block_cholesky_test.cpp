#define BOOST_TEST_MODULE dynamics_block_cholesky
#include <boost/test/unit_test.hpp>

// The block sparse Cholesky factorisation of the engines' implicit solves
// (common/src/block_cholesky.hpp), against Eigen's dense LLᵀ of the same matrix as the reference:
//
// (1) A jointed-mass-like system: a 14 x 9 grid of blocks coupled to their eight neighbours by
//     random 6 x 6 blocks, each block 6, 3 or 1 unknowns (deformable, rigid, and a size the
//     engines do not use), the diagonal made dominant by a factor 2, the couplings' scales
//     spread over 10⁰..10⁹ as a stiff joint next to a soft one. Cholesky's error does not see
//     a symmetric diagonal scaling, and scaled to a unit diagonal this matrix is within a
//     factor 2 of the identity (its condition below ~10), so both solves are exact to a few
//     hundred roundings (657 unknowns): the solutions must agree to 10⁻¹² relative, and
//     the residual be below 10⁻¹³ of the load (measured: 2·10⁻¹⁶ and 3·10⁻¹⁶).
// (2) The same matrix handed in as pieces: each coupling split into two terms, half of them at
//     (col, row) with the transposed value, the diagonals split in three. Same factorisation
//     order, so the same solution to the rounding of the sums (10⁻¹⁴ relative).
// (3) One solver object refactorising: the matrix of (1) with other values at the same places
//     (the kept analysis), then a smaller system (a new analysis), each against its dense solve
//     to 10⁻¹² as in (1).
// (4) A chain (each block coupled to the next): a tree has an ordering with no fill, which the
//     minimum degree finds, so L has exactly n - 1 blocks below its diagonal.
// (5) A matrix with an indefinite diagonal block is refused (factorize returns false); block
//     sizes outside 1..6 and terms outside the blocks are errors that say so.

#include <initializer_list>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>

#include "../common/src/block_cholesky.hpp"

namespace {

using rockcontact::dynamics::BlockCholesky;
using Term = BlockCholesky<6>::Term;
using Block = BlockCholesky<6>::Block;

struct System {
  std::vector<int> sizes;
  std::vector<Term> terms;
  Eigen::MatrixXd dense;
};

Eigen::Index start_of(const std::vector<int>& sizes, int block) {
  Eigen::Index s = 0;
  for (int i = 0; i < block; ++i) s += sizes[static_cast<std::size_t>(i)];
  return s;
}

void add_dense(System& system, const Term& t) {
  const auto& sizes = system.sizes;
  const int r = sizes[static_cast<std::size_t>(t.row)], c = sizes[static_cast<std::size_t>(t.col)];
  const Eigen::Index rs = start_of(sizes, t.row), cs = start_of(sizes, t.col);
  system.dense.block(rs, cs, r, c) += t.value.topLeftCorner(r, c);
  if (t.row != t.col) system.dense.block(cs, rs, c, r) += t.value.topLeftCorner(r, c).transpose();
}

// Case (1): a grid of nx x ny blocks, couplings to the 8 neighbours.
System grid_system(int nx, int ny, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> decade(0, 9);
  System system;
  const int n = nx * ny;
  for (int k = 0; k < n; ++k) system.sizes.push_back(k % 7 == 3 ? 3 : k % 11 == 5 ? 1 : 6);
  Eigen::Index unknowns = 0;
  for (const int s : system.sizes) unknowns += s;
  system.dense = Eigen::MatrixXd::Zero(unknowns, unknowns);
  std::vector<double> row_sum(static_cast<std::size_t>(unknowns), 0.0);
  std::vector<Term> couplings;
  for (int x = 0; x < nx; ++x) {
    for (int y = 0; y < ny; ++y) {
      for (const auto& [dx, dy] : {std::pair{1, 0}, {0, 1}, {1, 1}, {1, -1}}) {
        const int u = x + dx, v = y + dy;
        if (u >= nx || v < 0 || v >= ny) continue;
        Term t{x * ny + y, u * ny + v, Block::Zero()};
        const double scale = std::pow(10.0, decade(rng));
        for (int r = 0; r < 6; ++r) {
          for (int c = 0; c < 6; ++c) t.value(r, c) = scale * unit(rng);
        }
        couplings.push_back(t);
      }
    }
  }
  // Diagonal blocks: twice the row sums of |coupling| over the block's real unknowns, plus a
  // random symmetric part within that margin.
  std::vector<Block> diagonal(static_cast<std::size_t>(n), Block::Zero());
  for (const Term& t : couplings) {
    const int r = system.sizes[static_cast<std::size_t>(t.row)], c = system.sizes[static_cast<std::size_t>(t.col)];
    const Eigen::MatrixXd v = t.value.topLeftCorner(r, c).cwiseAbs();
    diagonal[static_cast<std::size_t>(t.row)].diagonal().head(r) += v.rowwise().sum();
    diagonal[static_cast<std::size_t>(t.col)].diagonal().head(c) += v.colwise().sum().transpose();
  }
  for (int k = 0; k < n; ++k) {
    Block& d = diagonal[static_cast<std::size_t>(k)];
    const int s = system.sizes[static_cast<std::size_t>(k)];
    d.diagonal() = 2.0 * d.diagonal() + Eigen::Matrix<double, 6, 1>::Constant(1.0);
    for (int r = 0; r < s; ++r) {
      for (int c = r + 1; c < s; ++c) {
        const double off = 0.1 * std::min(d(r, r), d(c, c)) * unit(rng) / 6.0;
        d(r, c) = d(c, r) = off;
      }
    }
    system.terms.push_back({k, k, d});
  }
  for (const Term& t : couplings) system.terms.push_back(t);
  for (const Term& t : system.terms) add_dense(system, t);
  return system;
}

Eigen::VectorXd random_load(Eigen::Index size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd b(size);
  for (Eigen::Index k = 0; k < size; ++k) b(k) = unit(rng);
  return b;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_grid_of_mixed_blocks_solves_as_the_dense_factorisation_does) {
  const System system = grid_system(14, 9, 2024);
  const Eigen::VectorXd b = random_load(system.dense.rows(), 7);
  const Eigen::LLT<Eigen::MatrixXd> dense(system.dense);
  BOOST_REQUIRE(dense.info() == Eigen::Success);
  const Eigen::VectorXd reference = dense.solve(b);
  BlockCholesky<6> solver;
  BOOST_REQUIRE(solver.factorize(system.sizes, system.terms));
  const Eigen::VectorXd x = solver.solve(b);
  BOOST_TEST((x - reference).norm() / reference.norm() < 1e-12);
  BOOST_TEST((system.dense * x - b).norm() / b.norm() < 1e-13);
}

BOOST_AUTO_TEST_CASE(terms_in_pieces_and_transposed_add_up_to_the_same_matrix) {
  const System whole = grid_system(10, 7, 99);
  std::vector<Term> pieces;
  bool flip = false;
  for (const Term& t : whole.terms) {
    if (t.row == t.col) {
      for (int k = 0; k < 3; ++k) pieces.push_back({t.row, t.col, t.value / 3.0});
      continue;
    }
    const Block first = 0.25 * t.value, second = t.value - first;
    pieces.push_back({t.row, t.col, first});
    if (flip) {
      pieces.push_back({t.col, t.row, second.transpose()});
    } else {
      pieces.push_back({t.row, t.col, second});
    }
    flip = !flip;
  }
  const Eigen::VectorXd b = random_load(whole.dense.rows(), 3);
  BlockCholesky<6> a, c;
  BOOST_REQUIRE(a.factorize(whole.sizes, whole.terms));
  BOOST_REQUIRE(c.factorize(whole.sizes, pieces));
  const Eigen::VectorXd xa = a.solve(b), xc = c.solve(b);
  BOOST_TEST((xa - xc).norm() / xa.norm() < 1e-14);
  BOOST_TEST((whole.dense * xc - b).norm() / b.norm() < 1e-13);
}

BOOST_AUTO_TEST_CASE(a_solver_refactorises_new_values_and_new_patterns) {
  const System first = grid_system(12, 8, 5);
  System second = first;  // the same places, other values: diagonals doubled, couplings halved
  second.dense.setZero();
  for (Term& t : second.terms) t.value *= t.row == t.col ? 2.0 : 0.5;
  for (const Term& t : second.terms) add_dense(second, t);
  const System third = grid_system(5, 4, 11);
  BlockCholesky<6> solver;
  for (const System* system : std::initializer_list<const System*>{&first, &second, &third}) {
    const Eigen::VectorXd b = random_load(system->dense.rows(), 13);
    const Eigen::VectorXd reference = Eigen::LLT<Eigen::MatrixXd>(system->dense).solve(b);
    BOOST_REQUIRE(solver.factorize(system->sizes, system->terms));
    BOOST_TEST((solver.solve(b) - reference).norm() / reference.norm() < 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(a_chain_factorises_without_fill) {
  const int n = 40;
  std::vector<int> sizes(n, 6);
  std::vector<Term> terms;
  for (int k = 0; k < n; ++k) {
    terms.push_back({k, k, 10.0 * Block::Identity()});
    if (k + 1 < n) terms.push_back({k, k + 1, -Block::Identity()});
  }
  BlockCholesky<6> solver;
  BOOST_REQUIRE(solver.factorize(sizes, terms));
  BOOST_TEST(solver.factor_blocks() == static_cast<std::size_t>(n - 1));
}

BOOST_AUTO_TEST_CASE(an_indefinite_matrix_and_bad_blocks_are_refused) {
  std::vector<int> sizes{6, 3};
  std::vector<Term> terms{{0, 0, Block::Identity()}, {1, 1, Block::Identity()}, {0, 1, Block::Zero()}};
  terms[1].value(2, 2) = -1.0;  // the rigid block's third unknown has a negative stiffness
  BlockCholesky<6> solver;
  BOOST_TEST(!solver.factorize(sizes, terms));
  terms[1].value(2, 2) = 1.0;
  terms[1].value(4, 4) = -1.0;  // past the rigid block's 3 unknowns: not read
  BOOST_TEST(solver.factorize(sizes, terms));
  const std::vector<int> too_big{6, 7};
  BOOST_CHECK_EXCEPTION(solver.factorize(too_big, terms), std::invalid_argument, [](const std::invalid_argument& e) {
    return std::string(e.what()).find("block 1 has 7 unknowns, not 1 to 6") != std::string::npos;
  });
  terms.push_back({0, 2, Block::Zero()});
  BOOST_CHECK_EXCEPTION(solver.factorize(sizes, terms), std::invalid_argument, [](const std::invalid_argument& e) {
    return std::string(e.what()).find("outside the 2 blocks") != std::string::npos;
  });
}
