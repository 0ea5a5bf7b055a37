#include "faults.hpp"

#include <utility>
#include <vector>

#include "run_command.hpp"

namespace hotmesh::test {
namespace {

/// The variables that ask the library for `faults`, the library first.
std::vector<std::pair<std::string, std::string>> variables(const Faults& faults) {
  std::vector<std::pair<std::string, std::string>> result;
  if (faults.kill_after_checkpoint <= 0 && faults.fail_allocation_after_checkpoint <= 0 &&
      faults.hold_cad_check.empty()) {
    return result;
  }
  result.emplace_back("LD_PRELOAD", HOTMESH_FAULTS_LIBRARY);
  if (faults.kill_after_checkpoint > 0) {
    result.emplace_back("HOTMESH_TEST_KILL_AFTER_CHECKPOINT", std::to_string(faults.kill_after_checkpoint));
  }
  if (faults.fail_allocation_after_checkpoint > 0) {
    result.emplace_back("HOTMESH_TEST_FAIL_ALLOCATION_AFTER_CHECKPOINT",
                        std::to_string(faults.fail_allocation_after_checkpoint));
  }
  if (!faults.hold_cad_check.empty()) result.emplace_back("HOTMESH_TEST_HOLD_CAD_CHECK", faults.hold_cad_check);
  return result;
}

}  // namespace

std::string fault_variables(const Faults& faults) {
  std::string words;
  for (const auto& [name, value] : variables(faults)) words += name + "=" + shell_quote(value) + " ";
  return words;
}

std::map<std::string, std::string> fault_environment(const Faults& faults) {
  const auto list = variables(faults);
  return {list.begin(), list.end()};
}

std::string mpirun_fault_options(const Faults& faults) {
  std::string words;
  for (const auto& [name, value] : variables(faults)) words += "-x " + name + "=" + shell_quote(value) + " ";
  return words;
}

}  // namespace hotmesh::test
