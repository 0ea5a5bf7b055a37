// Tests of the stiffness operator, K in node blocks summed from the element matrices (eqs.
// 9-10): agreement with the textbook assembly (in the nodes' order and renumbered), its block
// pattern, colouring, the reverse Cuthill-McKee order, and bit-identical results for any
// number of threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <numeric>

#include "hotmesh/deform/assembled_stiffness.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/deform/node_order.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "test_support.hpp"

namespace hotmesh::deform {
namespace {

std::vector<double> pseudo_random(std::size_t n) {
  std::vector<double> v(n);
  std::uint64_t s = 88172645463325252ull;
  for (auto& x : v) {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    x = static_cast<double>(s % 2001) / 1000.0 - 1.0;
  }
  return v;
}

/// `mesh` with the nodes numbered at random.
Mesh shuffled(const Mesh& mesh) { return test::shuffled_nodes(mesh, 7); }

/// The largest distance between the positions of two nodes of a cell.
NodeId bandwidth(const Mesh& mesh, const std::vector<NodeId>& position) {
  NodeId widest = 0;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    for (NodeId a : mesh.cells.nodes(c)) {
      for (NodeId b : mesh.cells.nodes(c)) {
        widest = std::max(widest, position[static_cast<std::size_t>(a)] - position[static_cast<std::size_t>(b)]);
      }
    }
  }
  return widest;
}

StiffnessOperator make_operator(const Mesh& mesh) {
  StiffnessOperator k(mesh, element_lame(mesh, {}), true);
  k.update(mesh.points);
  return k;
}

/// The blocks, the product (in chunks of rows, some of whose blocks reach past the next chunk
/// on the rings, whose numbering wraps around) and the diagonal against K assembled entry by
/// entry.
TEST(StiffnessOperator, NodeBlocksAgreeWithTheAssemblyOfEveryEntry) {
  for (Mesh given : {test::square_ring(6, 4, 0.3, 1.0), test::square_ring(4, 3, 0.3, 1.0, 2, 0.5),
                     test::hybrid_ring(6, 4, 0.3, 1.0, 0, 0.0, 1.0, 2), test::hybrid_ring(4, 3, 0.3, 1.0, 2, 0.5, 1.0, 1),
                     test::unit_square(40, 3), test::unit_cube(6)}) {
    test::jiggle_interior(given, 0.2);
    const std::array<Mesh, 2> numberings = {given, shuffled(given)};
    for (const Mesh& mesh : numberings) {
      const StiffnessOperator k = make_operator(mesh);
      const auto a = assemble_sparse(k.kernel(), mesh.points);
      const auto x = pseudo_random(k.size());
      std::vector<double> y(k.size());
      k.apply(x, y);
      const Eigen::VectorXd reference = a * Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
      const Eigen::Map<const Eigen::VectorXd> product(y.data(), static_cast<Eigen::Index>(y.size()));
      EXPECT_LT((product - reference).norm(), 1e-12 * reference.norm());
      std::vector<double> d(k.size());
      k.diagonal(d);
      for (std::size_t i = 0; i < d.size(); ++i) EXPECT_NEAR(d[i], a.coeff(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)), 1e-12 * std::abs(d[i]));
      EXPECT_LT((Eigen::SparseMatrix<double>(a.transpose()) - a).norm(), 1e-12 * a.norm());
      std::vector<double> blocks(k.size() * static_cast<std::size_t>(k.dofs_per_node()));
      k.diagonal_blocks(blocks);
      const auto dim = static_cast<std::size_t>(k.dofs_per_node());
      for (std::size_t n = 0; n < mesh.node_count(); ++n) {
        for (std::size_t r = 0; r < dim * dim; ++r) {
          const auto row = static_cast<Eigen::Index>(n * dim + r / dim), column = static_cast<Eigen::Index>(n * dim + r % dim);
          EXPECT_NEAR(blocks[n * dim * dim + r], a.coeff(row, column), 1e-12 * a.coeff(row, row)) << "node " << n;
        }
      }
      if (&mesh == &numberings[1]) {
        EXPECT_TRUE(k.renumbered());
      }
      EXPECT_GE(k.chunk_count(), 3u) << k.chunk_rows() << " rows a chunk";
    }
  }
}

/// Reverse Cuthill-McKee numbers every node once and keeps a long strip of quads banded by its
/// width, whatever the numbering it starts from; each part of a mesh in two parts is
/// numbered apart.
TEST(StiffnessOperator, ReverseCuthillMcKeeBandsAShuffledStrip) {
  const Mesh strip = shuffled(test::unit_square(60, 5));
  const NodeCells around(strip.cells, strip.node_count());
  const auto order = reverse_cuthill_mckee(strip.cells, around);
  ASSERT_EQ(order.size(), strip.node_count());
  std::vector<NodeId> position(order.size(), -1);
  for (std::size_t r = 0; r < order.size(); ++r) {
    ASSERT_EQ(position[static_cast<std::size_t>(order[r])], -1) << "node " << order[r] << " numbered twice";
    position[static_cast<std::size_t>(order[r])] = static_cast<NodeId>(r);
  }
  std::vector<NodeId> own(strip.node_count());
  std::iota(own.begin(), own.end(), NodeId{0});
  EXPECT_GT(bandwidth(strip, own), 100);
  EXPECT_LE(bandwidth(strip, position), 2 * 6 + 1);  // two columns of 6 nodes and one more
  EXPECT_LT(mean_spread(strip.cells, position), 0.05 * mean_spread(strip.cells, {}));

  Mesh two = test::unit_square(4, 4);  // and a second square beside it, sharing no node
  const auto offset = static_cast<NodeId>(two.node_count());
  const Mesh second = test::unit_square(4, 4);
  for (const auto& p : second.points) two.points.push_back({p[0] + 2.0, p[1], p[2]});
  for (std::size_t c = 0; c < second.cell_count(); ++c) {
    std::vector<NodeId> nodes;
    for (NodeId n : second.cells.nodes(c)) nodes.push_back(n + offset);
    two.cells.add(second.cells.type(c), nodes);
  }
  const auto parts = reverse_cuthill_mckee(two.cells, NodeCells(two.cells, two.node_count()));
  ASSERT_EQ(parts.size(), two.node_count());
  const auto first_part = [&](NodeId n) { return n < offset; };
  EXPECT_TRUE(std::is_partitioned(parts.begin(), parts.end(), first_part) ||
              std::is_partitioned(parts.begin(), parts.end(), [&](NodeId n) { return !first_part(n); }));
}

/// Every cell in one colour, no two cells of a colour on one node, a colour's cells in cell
/// order; returns the number of colours.
std::size_t expect_valid_coloring(const Mesh& mesh) {
  const CellColoring coloring = color_cells(mesh.cells, mesh.node_count());
  std::vector<int> seen(mesh.cell_count(), 0);
  for (std::size_t k = 0; k < coloring.colors(); ++k) {
    std::vector<char> used(mesh.node_count(), 0);
    for (auto i = coloring.offsets[k]; i < coloring.offsets[k + 1]; ++i) {
      const auto c = static_cast<std::size_t>(coloring.cells[static_cast<std::size_t>(i)]);
      ++seen[c];
      for (NodeId n : mesh.cells.nodes(c)) {
        EXPECT_FALSE(used[static_cast<std::size_t>(n)]) << "colour " << k << " node " << n;
        used[static_cast<std::size_t>(n)] = 1;
      }
      if (i > coloring.offsets[k]) {
        EXPECT_LT(coloring.cells[static_cast<std::size_t>(i - 1)], coloring.cells[static_cast<std::size_t>(i)]);
      }
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<std::ptrdiff_t>(mesh.cell_count()));
  return coloring.colors();
}

TEST(StiffnessOperator, ColoursNeverShareANode) {
  EXPECT_LE(expect_valid_coloring(test::square_ring(5, 3, 0.3, 1.0, 2, 1.0)), 10u);  // a structured hex mesh needs 8
  expect_valid_coloring(test::hybrid_ring(5, 3, 0.3, 1.0, 0, 0.0, 1.0, 1));
  expect_valid_coloring(test::hybrid_ring(5, 3, 0.3, 1.0, 2, 1.0, 1.0, 1));
}

/// Row i of K has one block for each node that shares a cell with i (itself included), and
/// half of them (the diagonal counted once) are stored: each in one of the two nodes' rows, the
/// diagonal first. A node of a hex mesh inside the block couples with 27.
TEST(StiffnessOperator, EachRowHoldsTheNodesThatShareACellWithItsNode) {
  for (const Mesh& mesh : {test::square_ring(5, 3, 0.3, 1.0, 3, 1.0), test::hybrid_ring(5, 3, 0.3, 1.0, 2, 1.0, 1.0, 1)}) {
    const StiffnessOperator k = make_operator(mesh);
    std::vector<std::vector<NodeId>> expected(mesh.node_count()), coupled(mesh.node_count());
    for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
      for (NodeId a : mesh.cells.nodes(c)) {
        for (NodeId b : mesh.cells.nodes(c)) expected[static_cast<std::size_t>(a)].push_back(b);
      }
    }
    std::size_t stored = 0;
    for (std::size_t i = 0; i < mesh.node_count(); ++i) {
      const auto nodes = k.stored_nodes(static_cast<NodeId>(i));
      ASSERT_FALSE(nodes.empty());
      EXPECT_EQ(nodes.front(), static_cast<NodeId>(i));
      for (NodeId q : nodes) {
        coupled[i].push_back(q);
        if (q != static_cast<NodeId>(i)) coupled[static_cast<std::size_t>(q)].push_back(static_cast<NodeId>(i));
      }
      stored += nodes.size();
    }
    std::size_t blocks = 0, most = 0;
    for (std::size_t i = 0; i < mesh.node_count(); ++i) {
      for (auto* row : {&expected[i], &coupled[i]}) std::sort(row->begin(), row->end());
      auto& row = expected[i];
      row.erase(std::unique(row.begin(), row.end()), row.end());
      EXPECT_EQ(coupled[i], row) << "row " << i;  // each coupling stored once
      blocks += row.size();
      most = std::max(most, row.size());
    }
    EXPECT_EQ(k.nonzero_blocks(), blocks);
    EXPECT_EQ(k.block_count(), stored);
    EXPECT_EQ(k.block_count(), (blocks + mesh.node_count()) / 2);
    if (mesh.cells.type(0) == ElementType::hex8) {
      EXPECT_EQ(most, 27u);
    }
  }
}

TEST(StiffnessOperator, BlocksAndProductAreBitIdenticalForAnyThreadCount) {
  // Large enough that the element loops run in parallel, colour by colour, and (the hex
  // block) the product too (mesh/include/hotmesh/mesh/parallel_loops.hpp). Threads take
  // cells and chunks of rows as they come (dynamic chunks): each thread count three times.
  Mesh ring = test::square_ring(16, 16, 0.3, 1.0, 4, 0.6);
  test::jiggle_interior(ring, 0.2);
  const auto xs = mesh::geometric_line(0.0, 1.0, 14, 1.1);
  const Mesh block = mesh::structured_hexes(xs, xs, xs);
  for (const Mesh* m : std::array<const Mesh*, 2>{&ring, &block}) {
    StiffnessOperator k(*m, element_lame(*m, {}), true);
    EXPECT_GE(k.chunk_count(), 3u);  // so that the threads share the rows of a product
    if (m == &block) {
      EXPECT_GE(static_cast<std::ptrdiff_t>(k.nonzero_blocks() * 9), mesh::kParallelProduct);
    }
    const auto x = pseudo_random(k.size());
    std::vector<std::vector<double>> results;
    const int saved = omp_get_max_threads();
    for (int threads : {1, 2, 3, 2, 3, 2}) {
      omp_set_num_threads(threads);
      k.update(m->points);
      std::vector<double> y(k.size());
      k.apply(x, y);
      results.push_back(y);
    }
    omp_set_num_threads(saved);
    for (std::size_t r = 1; r < results.size(); ++r) {
      EXPECT_EQ(std::memcmp(results[r].data(), results[0].data(), results[0].size() * sizeof(double)), 0);
    }
  }
}

/// The blocks' memory: 2 MiB aligned from 2 MiB on (where Linux can map it in huge pages),
/// the vector's values kept as it grows.
TEST(HugePageAllocator, AlignsLargeArraysToHugePagesAndKeepsTheValues) {
  std::vector<double, HugePageAllocator<double>> values(1000, 1.5);
  EXPECT_EQ(values[999], 1.5);
  values.resize(std::size_t{3} << 18, 2.5);  // 6 MiB
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(values.data()) % (std::uintptr_t{1} << 21), 0u);
  EXPECT_EQ(values[999], 1.5);
  EXPECT_EQ(values.back(), 2.5);
}

TEST(StiffnessOperator, RejectsCellsOfAnotherDimension) {
  Mesh mesh = test::unit_square(1, 1);
  mesh.cells = {};
  mesh.cells.add(ElementType::tri3, {0, 1, 2});
  mesh.cells.add(ElementType::tet4, {0, 1, 2, 3});
  EXPECT_THROW(StiffnessOperator(mesh, std::vector<Lame>(2), true), InputError);
}

}  // namespace
}  // namespace hotmesh::deform
