// hotmesh api: hotmesh::Case, a case read from its file or built in code, moved in memory (hotmesh/hotmesh.hpp).
#include <omp.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "hotmesh/io/calculix.hpp"
#include "library_state.hpp"

namespace hotmesh {
namespace {

io::PatchSpec& deflected_patch(io::Case& c, const std::string& patch, const char* call) {
  for (io::PatchSpec& p : c.patches) {
    if (p.name != patch) continue;
    if (p.role != deform::BoundaryRole::prescribed && p.role != deform::BoundaryRole::sliding) {
      throw InputError(fmt::format("{}: patch '{}' is {}: only prescribed and sliding patches follow a deflection",
                                   call, patch, deform::to_string(p.role)));
    }
    if (!p.deflection) {
      p.deflection.emplace();
      p.deflection->line = p.line;
    }
    return p;
  }
  std::string names;
  for (const io::PatchSpec& p : c.patches) names += (names.empty() ? "" : ", ") + p.name;
  throw InputError(fmt::format("{}: the case {} has no patch '{}' (its patches: {})", call, c.file.string(), patch, names));
}

geometry::SampleFrame frame_of(Frame frame, int columns, const io::Case& c, int dimension) {
  switch (frame) {
    case Frame::planar: return geometry::SampleFrame::planar;
    case Frame::cartesian: return geometry::SampleFrame::cartesian;
    case Frame::meridional: return geometry::SampleFrame::meridional;
    case Frame::automatic: break;
  }
  if (columns == 3) return geometry::SampleFrame::cartesian;
  return dimension == 3 || (dimension == 0 && c.axis) ? geometry::SampleFrame::meridional : geometry::SampleFrame::planar;
}

/// The deflection's arrays as a table: every value finite, r >= 0 in a meridional frame.
geometry::DeflectionSamples samples_of(const std::string& patch, std::span<const double> nodes,
                                       std::span<const double> displacements, int columns,
                                       geometry::SampleFrame frame) {
  const std::string call = fmt::format("set_deflection({})", patch);
  if (columns != 2 && columns != 3) throw InputError(fmt::format("{}: {} columns: give 2 (x, y or r, z) or 3 (x, y, z)", call, columns));
  const int wanted = frame == geometry::SampleFrame::cartesian ? 3 : 2;
  if (columns != wanted) {
    throw InputError(fmt::format("{}: a {} table has {} columns, not {}", call, geometry::to_string(frame), wanted, columns));
  }
  const std::size_t k = static_cast<std::size_t>(columns);
  if (nodes.empty() || nodes.size() % k != 0 || displacements.size() != nodes.size()) {
    throw InputError(fmt::format("{}: nodes has {} values and displacements {}: both need the same number of rows of {} "
                                 "values, at least one", call, nodes.size(), displacements.size(), columns));
  }
  geometry::DeflectionSamples samples;
  samples.frame = frame;
  samples.source = call;
  for (std::size_t j = 0; j < nodes.size() / k; ++j) {
    for (std::size_t i = 0; i < k; ++i) {
      for (const auto& [values, name] : {std::pair{nodes, "nodes"}, std::pair{displacements, "displacements"}}) {
        if (!std::isfinite(values[j * k + i])) {
          throw InputError(fmt::format("{}: {}[{}, {}] is {}: every value must be a finite number", call, name, j, i,
                                       values[j * k + i]));
        }
      }
    }
    const double* p = &nodes[j * k];
    const double* d = &displacements[j * k];
    if (frame == geometry::SampleFrame::meridional && p[0] < 0.0) {
      throw InputError(fmt::format("{}: nodes[{}, 0] = r = {} is negative: a meridional table gives r >= 0", call, j, p[0]));
    }
    samples.points.push_back({p[0], p[1], k == 3 ? p[2] : 0.0});
    samples.deflections.push_back({d[0], d[1], k == 3 ? d[2] : 0.0});
  }
  return samples;
}

}  // namespace

Case::Case(std::unique_ptr<State> state) : state_(std::move(state)) {}

Case::Case(const std::filesystem::path& case_file) : state_(std::make_unique<State>()) {
  start_library_logging();
  state_->c = io::read_case(case_file);
}

Case Case::from_mesh(const std::filesystem::path& mesh, const std::vector<std::pair<std::string, std::string>>& roles,
                     int increments) {
  start_library_logging();
  const std::filesystem::path path = std::filesystem::absolute(mesh).lexically_normal();
  // The case file these would make, read by the case file's own schema: the same checks.
  std::string text = fmt::format("mesh: {}\nsolver: {{increments: {}}}\npatches:\n", nlohmann::json(path.string()).dump(),
                                 increments);
  for (const auto& [patch, role] : roles) {
    text += fmt::format("  {}: {{role: {}}}\n", nlohmann::json(patch).dump(), nlohmann::json(role).dump());
  }
  auto state = std::make_unique<State>();
  state->c = io::parse_case(text, path.parent_path() / (path.stem().string() + ".yaml"));
  return Case(std::move(state));
}

Case::Case(Case&&) noexcept = default;
Case& Case::operator=(Case&&) noexcept = default;
Case::~Case() = default;

const std::filesystem::path& Case::file() const { return state_->c.file; }
std::filesystem::path Case::mesh_file() const { return state_->c.mesh; }

std::vector<std::string> Case::patches() const {
  std::vector<std::string> names;
  for (const io::PatchSpec& p : state_->c.patches) names.push_back(p.name);
  return names;
}

std::string Case::role(const std::string& patch) const {
  const io::PatchSpec* p = state_->c.find_patch(patch);
  if (p == nullptr) throw InputError(fmt::format("role: the case {} has no patch '{}'", state_->c.file.string(), patch));
  return std::string(deform::to_string(p->role));
}

void Case::set_deflection(const std::string& patch, std::span<const double> nodes, std::span<const double> displacements,
                          int columns, Frame frame) {
  io::Case& c = state_->c;
  const int dimension = state_->loaded ? state_->loaded->loaded.mesh.dimension : 0;
  geometry::DeflectionSamples samples = samples_of(patch, nodes, displacements, columns, frame_of(frame, columns, c, dimension));
  io::PatchSpec& p = deflected_patch(c, patch, "set_deflection");
  p.deflection->samples = std::move(samples);
  // No file holds it: the case file stands for it (in the inputs an output may not replace).
  p.deflection->file = c.file;
  p.deflection->files = {c.file};
  p.deflection->calculix.reset();
}

void Case::set_calculix_deflection(const std::string& patch, const std::filesystem::path& frd,
                                   const std::filesystem::path& inp, const std::string& node_set) {
  io::CalculixSelection selection{std::filesystem::absolute(frd).lexically_normal(),
                                  std::filesystem::absolute(inp).lexically_normal(), node_set, {}};
  io::CalculixTable table = io::read_calculix_table(selection);
  io::PatchSpec& p = deflected_patch(state_->c, patch, "set_calculix_deflection");
  p.deflection->file = selection.frd;
  p.deflection->files = table.files;
  p.deflection->samples = std::move(table.samples);
  p.deflection->calculix = io::CalculixNote{selection, table.kind, table.step, table.time, table.min_temperature,
                                            table.max_temperature};
}

void Case::set_threads(int threads) {
  if (threads < 0) throw InputError(fmt::format("set_threads: {} threads; give 0 (hotmesh chooses) or more", threads));
  state_->threads = threads;
}

void Case::set_progress(ProgressCallback progress) { state_->progress = std::move(progress); }

Result Case::deform() const {
  State& s = *state_;
  std::lock_guard lock(s.running);
  return run(nullptr);
}

Result Case::deform(const Result& previous) const {
  State& s = *state_;
  std::lock_guard lock(s.running);
  return run(&previous);
}

}  // namespace hotmesh
