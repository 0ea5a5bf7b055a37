// hotmesh api: hotmesh::Result, a mesh moved in memory, and the motion that makes it (hotmesh/hotmesh.hpp).
#include <omp.h>
#include <spdlog/spdlog.h>

#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/output_folder.hpp"
#include "hotmesh/io/restart_file.hpp"
#include "library_state.hpp"

namespace hotmesh {
namespace {

/// How a library's waiting threads wait: as the program that loaded it set libgomp up.
constexpr const char* kLibraryWaitPolicy = "libgomp's, as the program set it (OMP_WAIT_POLICY)";

/// The state a result leaves for the next coupling iteration, checked to be of `mesh`.
io::RestartState previous_state(const Result::State& previous, const mesh::Mesh& mesh, const io::Case& c) {
  if (!previous.motion.success) {
    throw InputError(fmt::format("deform(previous): the previous motion failed ({}): there is no state to continue "
                                 "from", previous.motion.message));
  }
  io::RestartState state = io::restart_state(previous.c, previous.loaded->loaded.mesh, previous.motion);
  if (state.mesh_fingerprint != io::mesh_fingerprint(mesh)) {
    throw InputError(fmt::format("deform(previous): the previous result moved the mesh {}, not this case's {}",
                                 previous.c.mesh.string(), c.mesh.string()));
  }
  return state;
}

/// The mesh's restart state for the run: `previous`'s in memory, else the case file's restart:.
std::optional<io::RestartState> restart_of(const io::Case& c, const mesh::Mesh& mesh, const Result::State* previous) {
  if (previous) return previous_state(*previous, mesh, c);
  if (!c.restart) return std::nullopt;
  io::RestartState state = io::read_restart(*c.restart, mesh);
  spdlog::info("restarting from {} ({} sliding nodes)", c.restart->string(), state.sliding.size());
  return state;
}

api::MotionSettings motion_settings(const ProgressCallback& progress, int increments) {
  api::MotionSettings settings;
  if (!progress) return settings;
  settings.newton = [&progress, increments](const deform::NewtonProgress& p) {
    progress({p.step.increment, increments, p.step.increment > increments, p.iteration, p.residual_reduction, 0.0,
              true});
  };
  settings.increment = [&progress, increments](const deform::IncrementRecord& r) {
    progress({r.increment, increments, r.corner_pass, 0, r.residual_reduction, r.min_scaled_jacobian, r.accepted});
  };
  return settings;
}

}  // namespace

Result Case::run(const Result* previous) const {
  State& s = *state_;
  const auto start = Clock::now();
  api::RunState run;
  api::RunTimings timings;
  if (!s.loaded) {
    auto loaded = std::make_shared<api::LoadedCase>();
    loaded->c = s.c;
    loaded->threads.wait = kLibraryWaitPolicy;
    api::load_case(*loaded, api::thread_request(s.threads > 0 ? s.threads : -1, "set_threads", s.c), run);
    s.loaded = std::move(loaded);
  } else {
    s.loaded->c = s.c;  // its deflections given since
  }
  omp_set_num_threads(s.loaded->threads.choice.threads);  // this thread's, as the first run chose
  const mesh::Mesh& mesh = s.loaded->loaded.mesh;
  timings.read = seconds_since(start);

  const std::optional<io::RestartState> restart =
      restart_of(s.c, mesh, previous ? previous->state_.get() : nullptr);
  std::optional<deform::MotionStart> motion_start;
  if (restart) motion_start = deform::MotionStart{restart->points, restart->sliding};
  auto t = Clock::now();
  auto r = std::make_unique<Result::State>();
  r->setup = api::set_up_shapes(*s.loaded, restart ? &*restart : nullptr);
  timings.shapes = seconds_since(t);

  api::MotionSettings settings = motion_settings(s.progress, s.c.solver.increments);
  settings.restart = motion_start ? &*motion_start : nullptr;
  r->motion = api::move_the_mesh(*s.loaded, r->setup, settings, run, start);
  api::log_motion(mesh, r->motion);
  if (!r->motion.success) spdlog::warn("{}", r->motion.message);
  timings.peak_memory_all_ranks = api::peak_memory_bytes();
  timings.wall = seconds_since(start);

  r->loaded = s.loaded;
  r->c = s.c;
  r->timings = timings;
  r->solver = mesh::solver_quality(mesh, r->motion.points, s.loaded->loaded.layer);
  r->points.reserve(r->motion.points.size());
  r->ids.reserve(r->motion.points.size());
  for (std::size_t n = 0; n < r->motion.points.size(); ++n) {
    const geometry::Vec3& x = r->motion.points[n];
    r->points.push_back({x.x, x.y, x.z});
    r->ids.push_back(mesh.node_id(static_cast<mesh::NodeId>(n)));
  }
  return Result(std::move(r));
}

Result::Result(std::unique_ptr<State> state) : state_(std::move(state)) {}
Result::Result(Result&&) noexcept = default;
Result& Result::operator=(Result&&) noexcept = default;
Result::~Result() = default;

bool Result::success() const { return state_->motion.success; }
const std::string& Result::message() const { return state_->motion.message; }
double Result::stage() const { return state_->motion.lambda_reached; }
int Result::dimension() const { return state_->loaded->loaded.mesh.dimension; }
std::span<const Point> Result::points() const { return state_->points; }
std::span<const std::int64_t> Result::node_ids() const { return state_->ids; }
std::span<const double> Result::scaled_jacobians() const { return state_->motion.quality; }
double Result::min_scaled_jacobian() const { return state_->motion.summary.min_scaled_jacobian; }

Quality Result::quality() const {
  const mesh::SolverQualitySummary& m = state_->solver.summary;
  return {state_->motion.summary.min_scaled_jacobian,
          state_->motion.summary.inverted_cells,
          m.max_non_orthogonality.value,
          m.mean_non_orthogonality,
          m.severely_non_orthogonal_faces,
          m.max_skewness.value,
          m.max_volume_ratio.value,
          m.max_aspect_ratio.value};
}

std::string Result::report() const {
  const State& s = *state_;
  return api::deform_report({}, s.c, s.loaded->loaded, s.setup, s.motion, s.solver, s.timings, s.loaded->threads, {});
}

void Result::write(const std::filesystem::path& folder) const {
  const State& s = *state_;
  // As `hotmesh deform` makes its output folder ready (without --force).
  const auto inputs = s.c.inputs();
  io::OutputFolder made = io::prepare_output_folder(folder, inputs, false);
  api::refuse_to_replace_checkpoint(folder, false);
  const auto names = api::output_names(s.c, s.loaded->loaded);
  for (const auto& name : names) io::refuse_overwriting_input(folder / name, inputs);
  io::remove_stale_temporaries(folder, names);
  api::RunTimings timings = s.timings;
  // The run's wall time goes on with the writing.
  const auto start = Clock::now() - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timings.wall));
  api::write_run_outputs(folder, s.c, *s.loaded, s.setup, s.motion, {}, timings, start);
  made.keep();
}

}  // namespace hotmesh
