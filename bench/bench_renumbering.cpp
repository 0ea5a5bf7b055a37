// hotmesh benchmark: does renumbering the nodes for locality make the stiffness product faster?
// The product y = K x (StiffnessOperator::apply, the inner loop of Jacobi-PCG) reads x and
// writes y at the nodes of each cell; the closer the numbers of a cell's nodes, the more of
// them share cache lines. For a 100^3 hex block and the stator-well sector, in the order the
// generator gives, shuffled at random (what a mesh from an unstructured mesher may look like),
// and renumbered by Boost.Graph's reverse Cuthill-McKee ordering (cells then sorted by their
// lowest new node), it prints the mean |i - j| over the node pairs of a cell and the time of one
// product, on one thread and on all.
//
//   ninja -C build bench_renumbering && build/bench/bench_renumbering [--quick]
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/node_order.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "machine_load.hpp"
#include "stator_well.hpp"
#include "timing.hpp"

namespace {

using hotmesh::bench::Clock;
using hotmesh::bench::median;
using hotmesh::bench::seconds_since;
using hotmesh::mesh::Mesh;
using hotmesh::mesh::NodeId;

/// `mesh` with node n renamed new_number[n] and the cells sorted by their lowest new node.
Mesh renumbered(const Mesh& mesh, const std::vector<NodeId>& new_number) {
  Mesh out;
  out.dimension = mesh.dimension;
  out.points.resize(mesh.points.size());
  for (std::size_t n = 0; n < mesh.points.size(); ++n) out.points[static_cast<std::size_t>(new_number[n])] = mesh.points[n];
  std::vector<std::pair<NodeId, std::size_t>> order;
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    NodeId lowest = static_cast<NodeId>(mesh.points.size());
    for (NodeId n : mesh.cells.nodes(c)) lowest = std::min(lowest, new_number[static_cast<std::size_t>(n)]);
    order.emplace_back(lowest, c);
  }
  std::sort(order.begin(), order.end());
  std::vector<NodeId> nodes;
  for (const auto& [lowest, c] : order) {
    nodes.clear();
    for (NodeId n : mesh.cells.nodes(c)) nodes.push_back(new_number[static_cast<std::size_t>(n)]);
    out.cells.add(mesh.cells.type(c), nodes);
  }
  return out;
}

std::vector<NodeId> shuffled_numbers(std::size_t nodes) {
  std::vector<NodeId> number(nodes);
  std::iota(number.begin(), number.end(), NodeId{0});
  std::shuffle(number.begin(), number.end(), std::mt19937(5));
  return number;
}

/// Reverse Cuthill-McKee on the graph of the cells' edges (Boost.Graph).
std::vector<NodeId> rcm_numbers(const Mesh& mesh) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS,
                                      boost::property<boost::vertex_color_t, boost::default_color_type,
                                                      boost::property<boost::vertex_degree_t, int>>>;
  std::vector<std::pair<NodeId, NodeId>> edges;
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    const auto nodes = mesh.cells.nodes(c);
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      for (std::size_t b = a + 1; b < nodes.size(); ++b) edges.emplace_back(std::minmax(nodes[a], nodes[b]));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Graph graph(mesh.points.size());
  for (const auto& [a, b] : edges) boost::add_edge(static_cast<std::size_t>(a), static_cast<std::size_t>(b), graph);
  std::vector<std::size_t> order(mesh.points.size());
  boost::cuthill_mckee_ordering(graph, order.rbegin(), boost::get(boost::vertex_color, graph), boost::make_degree_map(graph));
  std::vector<NodeId> number(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) number[order[k]] = static_cast<NodeId>(k);
  return number;
}

struct Seconds {
  double build = 0.0;    ///< the StiffnessOperator's pattern, its row order included
  double update = 0.0;   ///< StiffnessOperator::update, the K_e summed into the blocks
  double product = 0.0;  ///< StiffnessOperator::apply
  bool renumbered = false;
};

Seconds operator_seconds(const Mesh& mesh, int threads) {
  omp_set_num_threads(threads);
  const auto built = Clock::now();
  hotmesh::deform::StiffnessOperator k(mesh, hotmesh::deform::element_lame(mesh, {}), true);
  const double build = seconds_since(built);
  std::vector<double> updates, products;
  for (int run = 0; run < 3; ++run) {
    const auto start = Clock::now();
    k.update(mesh.points);
    updates.push_back(seconds_since(start));
  }
  std::vector<double> x(k.size(), 1.0), y(k.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 1.0 + 1e-3 * static_cast<double>(i % 97);
  k.apply(x, y);  // touch
  for (int run = 0; run < 5; ++run) {
    const auto start = Clock::now();
    k.apply(x, y);
    products.push_back(seconds_since(start));
  }
  return {build, median(updates), median(products), k.renumbered()};
}

void rows(std::string_view name, const Mesh& mesh) {
  const int cores = omp_get_num_procs();
  const auto row = [&](std::string_view order, const Mesh& m) {
    const hotmesh::bench::LoadProbe load;
    const Seconds one = operator_seconds(m, 1), all = operator_seconds(m, cores);
    fmt::print("| {} | {} | {} | {:.0f} | {} | {:.2f} | {:.3f} | {:.3f} | {:.3f} | {:.2f} |\n", name, m.cell_count(), order,
               hotmesh::deform::mean_spread(m.cells, {}), one.renumbered ? "yes" : "no", one.build, one.update, one.product, all.product, load.others());
  };
  row("as generated", mesh);
  row("RCM", renumbered(mesh, rcm_numbers(mesh)));
  const Mesh shuffled = renumbered(mesh, shuffled_numbers(mesh.node_count()));
  row("shuffled", shuffled);
  row("shuffled, then RCM", renumbered(shuffled, rcm_numbers(shuffled)));
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string_view(argv[1]) == "--quick";
  const int n = quick ? 20 : 100;
  const std::int64_t sector_cells = quick ? 20'000 : 1'000'000;
  fmt::print("### Node numbering and the product y = K x\n\n");
  fmt::print(
      "| mesh | cells | numbering | mean node spread in a cell | rows renumbered (RCM) by hotmesh | operator built s "
      "| update, 1 thread s | product, 1 thread s | product, {} threads s | other load |\n",
      omp_get_num_procs());
  fmt::print("|---|---:|---|---:|---|---:|---:|---:|---:|---:|\n");
  const auto line = hotmesh::mesh::uniform_line(0.0, 1.0, n);
  rows(fmt::format("hex block {}^3", n), hotmesh::mesh::structured_hexes(line, line, line));
  using namespace hotmesh::samples::stator_well;
  const auto loop = profile();
  const hotmesh::samples::BlockMesher mesher(block_layout(loop), spacing_field());
  const Size size = size_for_cells(mesher, sector_cells);
  rows("stator-well sector", sector_mesh(mesher.mesh(size.refinement), loop, size.theta_cells));
  fmt::print("\nMedian of 3 updates and 5 products each; the cells of every numbering sorted by their lowest node.\n");
  return 0;
}
