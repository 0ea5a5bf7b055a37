// hotmesh tests: a program built against the installed hotmesh package (find_package(hotmesh),
// hotmesh::hotmesh). Usage: move_ramp CASE.yaml TABLE.csv PATCH OUTPUT_FOLDER
// Reads the deflection table itself (x,y,dx,dy after its comment and header lines), gives it
// to the case in memory, moves the mesh, writes the outputs, checks the moved mesh against the
// case's deflected walls (hotmesh::check) and that a bad argument is a hotmesh::InputError.
// Exit code 0 when all of that holds.
#include <hotmesh/hotmesh.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

/// The x,y,dx,dy rows of a deflection table: `nodes` and `displacements`, two values per row.
void read_table(const char* path, std::vector<double>& nodes, std::vector<double>& displacements) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 'x') continue;
    std::istringstream row(line);
    double v[4];
    char comma;
    row >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3];
    nodes.insert(nodes.end(), {v[0], v[1]});
    displacements.insert(displacements.end(), {v[2], v[3]});
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: move_ramp CASE.yaml TABLE.csv PATCH OUTPUT_FOLDER\n";
    return 2;
  }
  std::vector<double> nodes, displacements;
  read_table(argv[2], nodes, displacements);
  hotmesh::Case c(argv[1]);
  c.set_deflection(argv[3], nodes, displacements, 2);
  const hotmesh::Result result = c.deform();
  if (!result.success()) {
    std::cerr << "the motion failed: " << result.message() << "\n";
    return 1;
  }
  result.write(argv[4]);
  const std::filesystem::path moved = std::filesystem::path(argv[4]) / "deformed.msh";
  const hotmesh::CheckResult check = hotmesh::check(moved, argv[1]);
  std::cout << "hotmesh " << hotmesh::version() << ": " << result.points().size() << " nodes, min scaled Jacobian "
            << result.min_scaled_jacobian() << ", check " << (check.passed ? "passed" : "FAILED") << "\n"
            << check.text;
  bool refused = false;
  try {
    std::vector<double> nan_nodes = nodes;
    nan_nodes[1] = std::nan("");
    c.set_deflection(argv[3], nan_nodes, displacements, 2);
  } catch (const hotmesh::InputError& e) {
    refused = true;
    std::cout << "refused as hotmesh::InputError: " << e.what() << "\n";
  }
  return check.passed && refused && result.min_scaled_jacobian() > 0.0 ? 0 : 1;
}
