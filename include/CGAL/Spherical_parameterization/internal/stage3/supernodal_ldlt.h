// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// A sparse L D L^T factorization (no pivoting, like Eigen's SimplicialLDLT) whose columns are grouped into supernodes:
// runs of columns with the same pattern below the diagonal, stored as dense panels, so that the factorization is
// made of dense products (Eigen's blocked kernels) instead of one sparse column at a time. The least-distortion
// steps (least_distortion.h) factorize a Hessian of two unknowns per vertex at every step; on CGAL's bunny00 the
// simplicial factorization was a third of their time, and on 100k vertices and more nearly all of it.
//
// The unknowns are ordered by METIS (nested dissection) on the first call, unless the caller ordered them or gave the
// blocks' order (set_block_order: the mesh's own, computed once for all its systems); later calls
// with the same pattern reuse the ordering, the elimination tree, the supernodes and where each entry of the matrix
// goes. Unknowns that come in blocks (a vertex's two tangent coordinates) are ordered by the blocks' graph, each
// block's unknowns kept together: METIS then orders half the nodes and a quarter of the edges.
//
// The method is the textbook one (elimination tree, column counts from the row subtrees, fundamental supernodes,
// right-looking updates scattered into the ancestors' panels); see Davis, "Direct Methods for Sparse Linear
// Systems", SIAM 2006, chapters 4 and 9.
//
// Large patterns (split_min_unknowns) are split in two: two disjoint groups of subtrees of the supernodal elimination
// tree, of about the same cost (nested dissection's two halves, usually), whose supernodes depend on their own group
// only, and the top of the tree (the separators above them). With set_parallel(true) the two groups are factorized at
// the same time (TBB); the second one's updates of the top go to a buffer of its own, added to the top's panels once
// both are done, so the sums are made in the same order either way: the factor is the same to the last bit with one
// thread or two (side_by_side.h says why that matters).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_SUPERNODAL_LDLT_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_SUPERNODAL_LDLT_H

#include <CGAL/Spherical_parameterization/internal/deferred_stop_signals.h>
#include <CGAL/Spherical_parameterization/internal/side_by_side.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <metis.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <functional>
#include <thread>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// Lists of values for the indices 0 to n - 1 in one array: each value is added twice, in the same order, first to
// count it (pass 0), then to store it (pass 1, after counted()).
template <typename T>
struct Compressed_lists
{
  explicit Compressed_lists(int n) : start(static_cast<std::size_t>(n) + 1, 0) {}

  void add(int pass, int list, const T& value)
  {
    if(pass == 0)
      ++start[static_cast<std::size_t>(list) + 1];
    else
      values[next[static_cast<std::size_t>(list)]++] = value;
  }

  void counted()
  {
    for(std::size_t i = 1; i < start.size(); ++i)
      start[i] += start[i - 1];
    values.resize(start.back());
    next.assign(start.begin(), start.end() - 1);
  }

  struct Range
  {
    const T* first;
    const T* last;
    const T* begin() const { return first; }
    const T* end() const { return last; }
  };
  Range of(int list) const
  {
    return {values.data() + start[static_cast<std::size_t>(list)],
            values.data() + start[static_cast<std::size_t>(list) + 1]};
  }

  std::vector<std::size_t> start, next;
  std::vector<T> values;
};

class Supernodal_ldlt
{
public:
  // `order_by_metis`: false keeps the unknowns' order (a caller that ordered them already). `stored`: the triangle of
  // the symmetric matrices read (the other one is ignored). `block_size`: unknowns b * block_size to
  // b * block_size + block_size - 1 form block b, ordered together (METIS orders the blocks' graph). On the Hessians of
  // least_distortion.h (blocks of 2), the first factorization, which includes the analysis, took 0.50 s instead of
  // 0.78 s on CGAL's bunny00 and 2.9 s instead of 4.0 s on c3d_igea, with as many entries in the factor (1% more or
  // less).
  explicit Supernodal_ldlt(bool order_by_metis = true, Eigen::UpLoType stored = Eigen::Lower, int block_size = 1)
    : m_order_by_metis(order_by_metis), m_lower(stored == Eigen::Lower), m_block_size(std::max(1, block_size))
  {}

  // The order of the blocks to use instead of METIS' or the unknowns' own (block_rank[b]: the position of block b; the
  // caller's fill-reducing order of the same graph, tangent_newton_system.h's elimination_rank()), from the next
  // analysis on. Ignored unless it is a permutation of the blocks (one entry per block, each position once).
  void set_block_order(std::vector<int> block_rank)
  {
    std::vector<char> taken(block_rank.size(), 0);
    for(int position : block_rank)
    {
      if(position < 0 || static_cast<std::size_t>(position) >= block_rank.size() || taken[position])
      {
        m_block_rank.clear();
        return;
      }
      taken[position] = 1;
    }
    m_block_rank = std::move(block_rank);
  }

  // Whether the two groups of a split pattern are factorized by two threads (the factor is the same either way).
  void set_parallel(bool parallel) { m_parallel = parallel; }

  // `stop`, when given, is asked between the supernodes of the numeric factorization, by the thread that called
  // factorize() only (a user's progress callback behind it need not be thread-safe), at most every
  // stop_check_supernodes of them: true abandons the factorization (factorize() returns false, stopped() is true; the
  // next call starts again from the matrix). A factorization of a brain cortex's Hessian takes a second or more, of a
  // 3.3M-face mesh's far more, and the command line waits 1.2 s for the iterations to stop after a signal.
  void set_stop(std::function<bool()> stop) { m_stop = std::move(stop); }
  bool stopped() const { return m_stop_asked.value.load(); }

  // False when a pivot is zero or not finite (as Eigen's SimplicialLDLT, which does not pivot either), or stopped.
  bool factorize(const Eigen::SparseMatrix<double>& matrix)
  {
    m_stop_asked.value = false;
    m_caller = std::this_thread::get_id();
    Eigen::SparseMatrix<double> compressed;
    if(!matrix.isCompressed())
    {
      compressed = matrix;
      compressed.makeCompressed();
    }
    const Eigen::SparseMatrix<double>& A = matrix.isCompressed() ? matrix : compressed;
    if(!m_analyzed || !has_analyzed_pattern(A))
    {
      if(!analyze(A))
        return false;
    }
    std::fill(m_values.begin(), m_values.end(), 0.);
    const double* a = A.valuePtr();
    for(std::size_t k = 0; k < m_scatter.size(); ++k)
      if(m_scatter[k] != skipped)
        m_values[m_scatter[k]] += a[k];
    return factorize_numeric();
  }

  // x = A^-1 x, or with `absolute_pivots` x = (L |D| L^T)^-1 x, each |pivot| at least `floor`.
  void solve_in_place(Eigen::VectorXd& x, bool absolute_pivots = false, double floor = 0.) const
  {
    Eigen::VectorXd* one[1] = {&x};
    solve_in_place(one, 1, absolute_pivots, floor);
  }

  // The same for `count` right-hand sides at once, each solved with the very operations of the one above (so to the
  // last bit as it would be alone), but the factor is read once for all: a solve reads every panel, and on a brain
  // cortex's Newton system one takes a tenth of a second, about as long as four of them do together.
  void solve_in_place(Eigen::VectorXd* const* xs, std::size_t count, bool absolute_pivots = false,
                      double floor = 0.) const
  {
    const Eigen::Index n = m_size;
    std::vector<Eigen::VectorXd> ys(count, Eigen::VectorXd(n));
    for(std::size_t c = 0; c < count; ++c)
      for(Eigen::Index i = 0; i < n; ++i)
        ys[c][i] = (*xs[c])[m_order[i]];
    Eigen::VectorXd gathered;
    for(std::size_t s = 0; s < m_first.size() - 1; ++s) // L y = b
    {
      const Eigen::Index f = m_first[s], k = m_first[s + 1] - f, m = rows_of(s);
      const Panel panel(m_values.data() + m_panel_start[s], m, k);
      const int* rows = m_rows.data() + m_row_start[s] + k;
      for(Eigen::VectorXd& y : ys)
      {
        auto segment = y.segment(f, k);
        panel.topLeftCorner(k, k).triangularView<Eigen::UnitLower>().solveInPlace(segment);
        if(m > k)
        {
          gathered.noalias() = panel.bottomRows(m - k) * segment;
          for(Eigen::Index q = 0; q < m - k; ++q)
            y[rows[q]] -= gathered[q];
        }
      }
    }
    for(Eigen::VectorXd& y : ys)
      for(Eigen::Index i = 0; i < n; ++i)
        y[i] /= absolute_pivots ? std::max(std::abs(m_pivots[i]), floor) : m_pivots[i];
    for(std::size_t s = m_first.size() - 1; s-- > 0;) // L^T x = y
    {
      const Eigen::Index f = m_first[s], k = m_first[s + 1] - f, m = rows_of(s);
      const Panel panel(m_values.data() + m_panel_start[s], m, k);
      const int* rows = m_rows.data() + m_row_start[s] + k;
      for(Eigen::VectorXd& y : ys)
      {
        auto segment = y.segment(f, k);
        if(m > k)
        {
          gathered.resize(m - k);
          for(Eigen::Index q = 0; q < m - k; ++q)
            gathered[q] = y[rows[q]];
          segment.noalias() -= panel.bottomRows(m - k).transpose() * gathered;
        }
        panel.topLeftCorner(k, k).triangularView<Eigen::UnitLower>().transpose().solveInPlace(segment);
      }
    }
    for(std::size_t c = 0; c < count; ++c)
      for(Eigen::Index i = 0; i < n; ++i)
        (*xs[c])[m_order[i]] = ys[c][i];
  }

  // Whether the pattern analyzed was split in two groups (see the file's comment).
  bool split() const { return m_split; }

  // The pivots D, in the factorization's order.
  const Eigen::VectorXd& pivots() const { return m_pivots; }

private:
  typedef Eigen::Map<Eigen::MatrixXd> Panel_map;
  typedef Eigen::Map<const Eigen::MatrixXd> Panel;
  static constexpr std::size_t skipped = static_cast<std::size_t>(-1);

  // The scatter map is only valid for the very pattern analyzed: a pattern with as many entries elsewhere is analyzed
  // again (a comparison of the index arrays, small next to a factorization).
  bool has_analyzed_pattern(const Eigen::SparseMatrix<double>& A) const
  {
    return A.rows() == m_size && static_cast<std::size_t>(A.nonZeros()) == m_pattern_rows.size()
           && std::equal(m_pattern_starts.begin(), m_pattern_starts.end(), A.outerIndexPtr())
           && std::equal(m_pattern_rows.begin(), m_pattern_rows.end(), A.innerIndexPtr());
  }

  bool in_stored_triangle(int row, int column) const { return m_lower ? row >= column : row <= column; }

  Eigen::Index rows_of(std::size_t s) const { return m_row_start[s + 1] - m_row_start[s]; }

  bool analyze(const Eigen::SparseMatrix<double>& A)
  {
    m_analyzed = false;
    const int n = static_cast<int>(A.rows());
    m_size = A.rows();
    m_pattern_starts.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    m_pattern_rows.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    // The graph of A (both triangles, no diagonal, each list sorted) for METIS. Here and below, lists are built in
    // compressed arrays (counted, then filled): a vector per row cost a third of the analysis on a brain cortex.
    std::vector<idx_t> xadj(n + 1, 0), adjncy;
    {
      auto for_each_stored_edge = [&](auto&& visit) {
        for(int j = 0; j < n; ++j)
          for(Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
            if(in_stored_triangle(static_cast<int>(it.row()), j) && it.row() != j)
              visit(static_cast<int>(it.row()), j);
      };
      Compressed_lists<idx_t> all(n); // each edge in both lists, as stored
      for(int pass = 0; pass < 2; ++pass)
      {
        for_each_stored_edge([&](int r, int c) {
          all.add(pass, c, r);
          all.add(pass, r, c);
        });
        if(pass == 0)
          all.counted();
      }
      adjncy.reserve(all.values.size());
      for(int i = 0; i < n; ++i)
      {
        const auto begin = all.values.begin() + static_cast<std::ptrdiff_t>(all.start[static_cast<std::size_t>(i)]);
        const auto end = all.values.begin() + static_cast<std::ptrdiff_t>(all.start[static_cast<std::size_t>(i) + 1]);
        std::sort(begin, end);
        adjncy.insert(adjncy.end(), begin, std::unique(begin, end)); // a pattern may store an entry twice
        xadj[i + 1] = static_cast<idx_t>(adjncy.size());
      }
    }
    m_order.resize(n);
    std::vector<int> position(n);
    {
      std::vector<idx_t> perm(n), iperm(n);
      idx_t vertices = n;
      bool ordered = false; // by METIS or the order given; otherwise (no off-diagonal entry, or METIS failed) as given
      const int given_block = m_block_size;
      if(!m_block_rank.empty() && static_cast<std::size_t>(n) == m_block_rank.size() * static_cast<std::size_t>(m_block_size))
      {
        for(int block = 0; block < n / given_block; ++block)
          for(int q = 0; q < given_block; ++q)
            perm[m_block_rank[block] * given_block + q] = block * given_block + q;
        ordered = true;
      }
      else if(m_order_by_metis && !adjncy.empty())
      {
        const int b = n % m_block_size == 0 ? m_block_size : 1;
        std::vector<idx_t> block_xadj, block_adjncy;
        if(b > 1)
        {
          // The blocks' graph: block i / b and block j / b adjacent when unknowns i and j are.
          const int blocks = n / b;
          std::vector<int> last_seen(blocks, -1);
          block_xadj.assign(1, 0);
          for(int block = 0; block < blocks; ++block)
          {
            for(int i = block * b; i < (block + 1) * b; ++i)
              for(idx_t k = xadj[i]; k < xadj[i + 1]; ++k)
              {
                const int other = static_cast<int>(adjncy[k]) / b;
                if(other != block && last_seen[other] != block)
                {
                  last_seen[other] = block;
                  block_adjncy.push_back(other);
                }
              }
            block_xadj.push_back(static_cast<idx_t>(block_adjncy.size()));
          }
          vertices = blocks;
        }
        const Metis_call_guard metis_call; // see deferred_stop_signals.h
        ordered = !(b > 1 && block_adjncy.empty())
                  && METIS_NodeND(&vertices, b > 1 ? block_xadj.data() : xadj.data(),
                                  b > 1 ? block_adjncy.data() : adjncy.data(), nullptr, nullptr, perm.data(),
                                  iperm.data())
                         == METIS_OK;
        if(ordered && b > 1)
          for(int block = vertices; block-- > 0;) // perm[k]: the block eliminated k-th; expanded to its unknowns
            for(int q = b; q-- > 0;)
              perm[block * b + q] = perm[block] * b + q;
      }
      for(int i = 0; i < n; ++i)
      {
        m_order[i] = ordered ? static_cast<int>(perm[i]) : i; // row i of the factor is row m_order[i] of A
        position[m_order[i]] = i;
      }
    }
    // The permuted lower triangle's pattern by columns (rows below the diagonal) and by rows (the columns left of it).
    Compressed_lists<int> below(n), left(n);
    for(int pass = 0; pass < 2; ++pass)
    {
      for(int i = 0; i < n; ++i)
        for(idx_t k = xadj[i]; k < xadj[i + 1]; ++k)
        {
          const int p = position[i], q = position[adjncy[k]];
          if(p > q)
          {
            below.add(pass, q, p);
            left.add(pass, p, q);
          }
        }
      if(pass == 0)
      {
        below.counted();
        left.counted();
      }
    }
    // The elimination tree (Liu's algorithm, with path compression through `ancestor`).
    std::vector<int> parent(n, -1), ancestor(n, -1);
    for(int i = 0; i < n; ++i)
      for(int k : left.of(i))
        for(int r = k; r != -1 && r < i;)
        {
          const int next = ancestor[r];
          ancestor[r] = i;
          if(next == -1)
          {
            parent[r] = i;
            break;
          }
          r = next;
        }
    // Column counts of L (diagonal included): row i of L is the subtree of the tree reached from left[i] up to i.
    std::vector<int> count(n, 1), mark(n, -1);
    for(int i = 0; i < n; ++i)
    {
      mark[i] = i;
      for(int k : left.of(i))
        for(int r = k; r != -1 && mark[r] != i; r = parent[r])
        {
          ++count[r];
          mark[r] = i;
        }
    }
    // Fundamental supernodes: column j joins column j - 1's when j - 1 is its only child and their patterns nest.
    std::vector<int> children(n, 0);
    for(int j = 0; j < n; ++j)
      if(parent[j] != -1)
        ++children[parent[j]];
    m_first.clear();
    std::vector<int> owner(n);
    for(int j = 0; j < n; ++j)
    {
      const bool joins = j > 0 && parent[j - 1] == j && children[j] == 1 && count[j - 1] == count[j] + 1;
      if(!joins)
        m_first.push_back(j);
      owner[j] = static_cast<int>(m_first.size()) - 1;
    }
    m_first.push_back(n);
    const std::size_t supernodes = m_first.size() - 1;
    // Each supernode's rows: its columns, the rows of A below them, and the rows of its children's supernodes below it.
    std::vector<std::vector<int>> child_supernodes(supernodes);
    for(std::size_t s = 0; s < supernodes; ++s)
    {
      const int last = m_first[s + 1] - 1;
      if(parent[last] != -1)
        child_supernodes[owner[parent[last]]].push_back(static_cast<int>(s));
    }
    m_row_start.assign(1, 0);
    m_rows.clear();
    m_panel_start.assign(1, 0);
    std::fill(mark.begin(), mark.end(), -1);
    std::vector<int> rows;
    for(std::size_t s = 0; s < supernodes; ++s)
    {
      const int f = m_first[s], l = m_first[s + 1] - 1;
      rows.clear();
      for(int j = f; j <= l; ++j)
      {
        rows.push_back(j);
        mark[j] = static_cast<int>(s);
      }
      auto add = [&](int r) {
        if(r > l && mark[r] != static_cast<int>(s))
        {
          mark[r] = static_cast<int>(s);
          rows.push_back(r);
        }
      };
      for(int j = f; j <= l; ++j)
        for(int r : below.of(j))
          add(r);
      for(int c : child_supernodes[s])
        for(std::size_t q = m_row_start[c]; q < m_row_start[c + 1]; ++q)
          add(m_rows[q]);
      std::sort(rows.begin() + (l - f + 1), rows.end());
      if(static_cast<int>(rows.size()) != count[f])
        return false; // cannot happen: the symbolic steps disagree
      m_rows.insert(m_rows.end(), rows.begin(), rows.end());
      m_row_start.push_back(m_rows.size());
      m_panel_start.push_back(m_panel_start.back() + rows.size() * static_cast<std::size_t>(l - f + 1));
    }
    split_in_two(parent, owner, child_supernodes);
    m_values.assign(m_panel_start.back(), 0.);
    m_pivots.resize(n);
    // Where each stored entry of A's lower triangle goes in the panels.
    m_scatter.assign(static_cast<std::size_t>(A.nonZeros()), skipped);
    std::vector<int> slot(n, -1);
    Compressed_lists<std::pair<int, int>> entries_of_column(n); // (permuted row, index in A) of each permuted column
    for(int pass = 0; pass < 2; ++pass)
    {
      for(int j = 0; j < n; ++j)
        for(int e = A.outerIndexPtr()[j]; e < A.outerIndexPtr()[j + 1]; ++e)
          if(in_stored_triangle(A.innerIndexPtr()[e], j))
          {
            const int p = position[A.innerIndexPtr()[e]], q = position[j];
            entries_of_column.add(pass, std::min(p, q), {std::max(p, q), e});
          }
      if(pass == 0)
        entries_of_column.counted();
    }
    for(std::size_t s = 0; s < supernodes; ++s)
    {
      const int f = m_first[s], k = m_first[s + 1] - f;
      const std::size_t m = m_row_start[s + 1] - m_row_start[s];
      for(std::size_t q = 0; q < m; ++q)
        slot[m_rows[m_row_start[s] + q]] = static_cast<int>(q);
      for(int c = 0; c < k; ++c)
        for(const std::pair<int, int>& entry : entries_of_column.of(f + c))
          m_scatter[static_cast<std::size_t>(entry.second)] =
              m_panel_start[s] + static_cast<std::size_t>(c) * m + slot[entry.first];
    }
    m_analyzed = true;
    return true;
  }

  // The two groups of subtrees and the top (see the file's comment): m_group[s] is 0 or 1, or top_group. The split
  // starts from the roots, and while the costlier group carries more than 55% of the groups' cost, the costliest
  // subtree gives its root to the top and its children to the groups (largest first, each to the cheaper group).
  // No split (every supernode in group 0) below split_min_unknowns or where no balanced split is found.
  void split_in_two(const std::vector<int>& parent, const std::vector<int>& owner,
                    const std::vector<std::vector<int>>& child_supernodes)
  {
    const std::size_t supernodes = m_first.size() - 1;
    m_group.assign(supernodes, 0);
    m_top_offset.clear();
    m_buffer.clear();
    m_split = false;
    if(m_size < split_min_unknowns)
      return;
    // Each supernode's cost (its panel, then its update of the rows below) and its subtree's (children come first).
    std::vector<int> parent_supernode(supernodes, -1);
    std::vector<double> subtree_cost(supernodes, 0.);
    for(std::size_t s = 0; s < supernodes; ++s)
    {
      const double k = m_first[s + 1] - m_first[s], m = static_cast<double>(rows_of(s));
      subtree_cost[s] += k * k * m + (m - k) * (m - k) * k;
      const int last_parent = parent[static_cast<std::size_t>(m_first[s + 1] - 1)];
      if(last_parent != -1)
      {
        parent_supernode[s] = owner[static_cast<std::size_t>(last_parent)];
        subtree_cost[static_cast<std::size_t>(parent_supernode[s])] += subtree_cost[s];
      }
    }
    std::vector<int> candidates, assigned;
    for(std::size_t s = 0; s < supernodes; ++s)
      if(parent_supernode[s] == -1)
        candidates.push_back(static_cast<int>(s));
    std::vector<char> top(supernodes, 0);
    auto costlier = [&](int a, int b) { return subtree_cost[a] > subtree_cost[b] || (subtree_cost[a] == subtree_cost[b] && a < b); };
    bool balanced = false;
    for(int round = 0; round < 64 && !candidates.empty(); ++round)
    {
      std::sort(candidates.begin(), candidates.end(), costlier);
      double load[2] = {0., 0.};
      assigned.assign(candidates.size(), 0);
      for(std::size_t c = 0; c < candidates.size(); ++c)
      {
        assigned[c] = load[1] < load[0] ? 1 : 0;
        load[assigned[c]] += subtree_cost[static_cast<std::size_t>(candidates[c])];
      }
      if(load[1] > 0. && std::max(load[0], load[1]) <= 0.55 * (load[0] + load[1]))
      {
        balanced = true;
        break;
      }
      const int costliest = candidates.front();
      if(child_supernodes[static_cast<std::size_t>(costliest)].empty())
        break;
      top[static_cast<std::size_t>(costliest)] = 1;
      candidates.erase(candidates.begin());
      candidates.insert(candidates.end(), child_supernodes[static_cast<std::size_t>(costliest)].begin(),
                        child_supernodes[static_cast<std::size_t>(costliest)].end());
    }
    if(!balanced)
      return;
    std::vector<int> root_group(supernodes, -1);
    for(std::size_t c = 0; c < candidates.size(); ++c)
      root_group[static_cast<std::size_t>(candidates[c])] = assigned[c];
    for(std::size_t s = supernodes; s-- > 0;) // parents first
      m_group[s] = top[s] ? top_group
                   : root_group[s] != -1 ? root_group[s]
                                         : m_group[static_cast<std::size_t>(parent_supernode[s])];
    m_top_offset.assign(supernodes, 0);
    std::size_t top_size = 0;
    for(std::size_t s = 0; s < supernodes; ++s)
      if(m_group[s] == top_group)
      {
        m_top_offset[s] = top_size;
        top_size += m_panel_start[s + 1] - m_panel_start[s];
      }
    m_buffer.assign(top_size, 0.);
    m_split = true;
  }

  // What one thread of factorize_numeric() works with.
  struct Workspace
  {
    std::vector<int> slot;
    Eigen::MatrixXd update, positive, negative, scaled;
  };

  bool factorize_numeric()
  {
    if(!m_split)
    {
      Workspace all;
      return eliminate_group(0, nullptr, all);
    }
    std::fill(m_buffer.begin(), m_buffer.end(), 0.);
    bool done[2] = {false, false};
    side_by_side(
        m_parallel, [&]() { done[0] = eliminate_group(0, nullptr, m_workspaces[0]); },
        [&]() { done[1] = eliminate_group(1, m_buffer.data(), m_workspaces[1]); });
    if(!done[0] || !done[1])
      return false;
    for(std::size_t s = 0; s + 1 < m_first.size(); ++s)
      if(m_group[s] == top_group)
        for(std::size_t e = 0; e < m_panel_start[s + 1] - m_panel_start[s]; ++e)
          m_values[m_panel_start[s] + e] += m_buffer[m_top_offset[s] + e];
    return eliminate_group(top_group, nullptr, m_workspaces[0]);
  }

  // The supernodes of `group`, in order: each one's panel factorized, then its update of the rows below scattered
  // into their supernodes' panels, those of the top into `top_buffer` when given (the second group of a split).
  bool eliminate_group(int group, double* top_buffer, Workspace& workspace)
  {
    const std::size_t supernodes = m_first.size() - 1;
    std::vector<int>& slot = workspace.slot;
    slot.assign(static_cast<std::size_t>(m_size), -1);
    Eigen::MatrixXd &update = workspace.update, &positive = workspace.positive, &negative = workspace.negative,
                    &scaled = workspace.scaled;
    std::size_t done = 0;
    for(std::size_t s = 0; s < supernodes; ++s)
    {
      if(m_group[s] != group)
        continue;
      if(++done % stop_check_supernodes == 0 && stop_asked())
        return false;
      const Eigen::Index f = m_first[s], k = m_first[s + 1] - f, m = rows_of(s);
      Panel_map panel(m_values.data() + m_panel_start[s], m, k);
      // The panel's own columns (L D L^T of the diagonal block and the rows below it), by blocks of panel_block
      // columns: rank-1 updates within a block, then the columns right of it updated by one matrix product. Column by
      // column across the whole panel, those updates were 37% of a factorization of bigbrain's Hessian pattern
      // (memory-bound: each reads and writes the rest of the panel); blocked, 1.6 to 1.75 s instead of 1.9 to 2.0 s.
      for(Eigen::Index block = 0; block < k; block += panel_block)
      {
        const Eigen::Index width = std::min(panel_block, k - block), end = block + width;
        for(Eigen::Index j = block; j < end; ++j)
        {
          const double d = panel(j, j);
          if(!(d != 0.) || !std::isfinite(d))
            return false;
          m_pivots[f + j] = d;
          panel.col(j).tail(m - j - 1) /= d;
          if(j + 1 < end)
            panel.block(j + 1, j + 1, m - j - 1, end - j - 1).noalias() -=
                panel.col(j).tail(m - j - 1) * (d * panel.col(j).segment(j + 1, end - j - 1)).transpose();
        }
        if(end < k) // the columns right of the block (their entries above the diagonal are not used)
        {
          scaled = panel.block(end, block, k - end, width) * m_pivots.segment(f + block, width).asDiagonal();
          panel.block(end, end, m - end, k - end).noalias() -=
              panel.block(end, block, m - end, width) * scaled.transpose();
        }
      }
      if(m == k)
        continue;
      // The update of the rows below, L21 D L21^T, split by the pivots' signs into two symmetric rank updates.
      const Eigen::Index below = m - k;
      Eigen::Index positives = 0;
      for(Eigen::Index j = 0; j < k; ++j)
        positives += m_pivots[f + j] > 0.;
      positive.resize(below, positives);
      negative.resize(below, k - positives);
      for(Eigen::Index j = 0, p = 0, q = 0; j < k; ++j)
      {
        const double d = m_pivots[f + j];
        if(d > 0.)
          positive.col(p++) = std::sqrt(d) * panel.col(j).tail(below);
        else
          negative.col(q++) = std::sqrt(-d) * panel.col(j).tail(below);
      }
      update.setZero(below, below);
      if(positives > 0)
        update.selfadjointView<Eigen::Lower>().rankUpdate(positive, 1.);
      if(positives < k)
        update.selfadjointView<Eigen::Lower>().rankUpdate(negative, -1.);
      // Scattered into the supernodes that own the rows below, column by column.
      const int* rows = m_rows.data() + m_row_start[s] + k;
      int target = -1;
      for(Eigen::Index c = 0; c < below; ++c)
      {
        const int column = rows[c];
        if(target == -1 || column >= m_first[target + 1])
        {
          target = static_cast<int>(std::upper_bound(m_first.begin(), m_first.end(), column) - m_first.begin()) - 1;
          for(std::size_t q = m_row_start[target]; q < m_row_start[target + 1]; ++q)
            slot[m_rows[q]] = static_cast<int>(q - m_row_start[target]);
        }
        const std::size_t height = m_row_start[target + 1] - m_row_start[target];
        const std::size_t offset = static_cast<std::size_t>(column - m_first[target]) * height;
        double* destination = top_buffer != nullptr && m_group[static_cast<std::size_t>(target)] == top_group
                                   ? top_buffer + m_top_offset[static_cast<std::size_t>(target)] + offset
                                   : m_values.data() + m_panel_start[target] + offset;
        for(Eigen::Index r = c; r < below; ++r)
          destination[slot[rows[r]]] -= update(r, c);
      }
    }
    return true;
  }

  // Whether the factorization is to be abandoned (set_stop): asked of `m_stop` on the calling thread only; the other
  // thread sees the answer.
  bool stop_asked()
  {
    if(m_stop_asked.value.load(std::memory_order_relaxed))
      return true;
    if(m_stop && std::this_thread::get_id() == m_caller && m_stop())
      m_stop_asked.value = true;
    return m_stop_asked.value.load(std::memory_order_relaxed);
  }

  static constexpr std::size_t stop_check_supernodes = 16;
  static constexpr Eigen::Index panel_block = 64; // 32 and 128 measured alike on bigbrain's pattern; 64 the fastest
  // Patterns split in two from this size on (10,000 vertices of the least-distortion Hessians): below it, the second
  // thread's start costs about what it saves.
  static constexpr Eigen::Index split_min_unknowns = 20000;
  static constexpr int top_group = -1;
  bool m_order_by_metis, m_lower;
  bool m_parallel = false;
  bool m_split = false;
  std::vector<int> m_group;              // each supernode's group: 0, 1 or top_group (split_in_two)
  std::vector<std::size_t> m_top_offset; // a top supernode's panel in m_buffer
  std::vector<double> m_buffer;          // the second group's updates of the top
  Workspace m_workspaces[2];
  int m_block_size;
  bool m_analyzed = false;
  Eigen::Index m_size = 0;
  std::vector<int> m_pattern_starts, m_pattern_rows; // the pattern analyzed (compressed column storage)
  std::vector<int> m_order;                  // row i of the factor is row m_order[i] of the matrix
  std::vector<int> m_first;                  // first column of each supernode, then the size
  std::vector<std::size_t> m_row_start;      // each supernode's rows in m_rows
  std::vector<int> m_rows;                   // its columns first, then the rows below, increasing
  std::vector<std::size_t> m_panel_start;    // each supernode's dense panel (column-major, all its rows)
  std::vector<int> m_block_rank; // set_block_order()
  std::vector<double> m_values;
  std::vector<std::size_t> m_scatter;        // where each stored entry of the matrix goes in m_values
  Eigen::VectorXd m_pivots;
  std::function<bool()> m_stop;
  // Written by the calling thread, read by the other one; a copy starts unset (factorize() resets it anyway).
  struct Stop_flag
  {
    std::atomic<bool> value{false};
    Stop_flag() = default;
    Stop_flag(const Stop_flag&) {}
    Stop_flag& operator=(const Stop_flag&) { return *this; }
  } m_stop_asked;
  std::thread::id m_caller;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_SUPERNODAL_LDLT_H
