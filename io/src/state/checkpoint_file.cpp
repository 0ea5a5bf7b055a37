// hotmesh io: checkpoint files (checkpoint.hmc), to resume an interrupted run.
#include "hotmesh/io/checkpoint_file.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "state/binary_file.hpp"
#include "header_integers.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/restart_file.hpp"

namespace hotmesh::io {
namespace {

constexpr std::string_view kMagic = "HOTMESH-CHECKPOINT\n";
/// Version 2 holds the pieces of a split increment left (`split_pieces`) where version 1 held
/// every step left (`remaining`, 31 bytes per increment of the run). Version 3 appends the s
/// and face of each projection hint (surfaces' parameters) after version 2's arrays, which hold
/// t, with a checksum of their own. Version 4 appends the mesh at the start of the last
/// accepted step (the predictor's secant; none in a checkpoint of an older version, whose
/// resumed run then predicts its first increment from the undeformed mesh). All are read.
constexpr int kVersion = 4;
constexpr int kOldestVersion = 1;
constexpr std::string_view kKind = "checkpoint file";

using nlohmann::json;

/// JSON has no NaN or infinity; a diverged Newton step records them.
json number(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}

double number_from(const json& j) {
  if (!j.is_string()) return j.get<double>();
  const auto text = j.get<std::string>();
  if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (text == "inf") return std::numeric_limits<double>::infinity();
  if (text == "-inf") return -std::numeric_limits<double>::infinity();
  throw std::runtime_error("'" + text + "' is not a number");
}

json record_json(const deform::IncrementRecord& r) {
  json newton = json::array();
  for (const auto& s : r.newton) {
    newton.push_back({number(s.residual), s.pcg_iterations, s.pcg_converged, number(s.pcg_reduction),
                      number(s.linear_tolerance), number(s.max_projection), s.linear_newton_norm});
  }
  return {{"increment", r.increment},
          {"stage", {r.lambda_begin, r.lambda_end}},
          {"split_depth", r.split_depth},
          {"newton", newton},
          {"converged", r.converged},
          {"accepted", r.accepted},
          {"residual_reduction", number(r.residual_reduction)},
          {"min_scaled_jacobian", number(r.min_scaled_jacobian)},
          {"inverted_cells", r.inverted_cells},
          {"worst_cell", r.worst_cell},
          {"max_normal_slip", number(r.max_normal_slip)},
          {"seconds", r.seconds},
          {"failure", r.failure}};
}

deform::IncrementRecord record_from_json(const json& j) {
  deform::IncrementRecord r;
  r.increment = detail::integer_value<int>(j.at("increment"));
  r.lambda_begin = j.at("stage").at(0).get<double>();
  r.lambda_end = j.at("stage").at(1).get<double>();
  r.split_depth = detail::integer_value<int>(j.at("split_depth"));
  for (const json& s : j.at("newton")) {
    r.newton.push_back({.residual = number_from(s.at(0)),
                        .pcg_iterations = detail::integer_value<int>(s.at(1)),
                        .pcg_converged = s.at(2).get<bool>(),
                        .pcg_reduction = number_from(s.at(3)),
                        .linear_tolerance = number_from(s.at(4)),
                        .max_projection = number_from(s.at(5)),
                        // Absent from the checkpoints of hotmesh before 2026-11-22: not recorded.
                        .linear_newton_norm = s.size() > 6 && s.at(6).get<bool>()});
  }
  r.converged = j.at("converged").get<bool>();
  r.accepted = j.at("accepted").get<bool>();
  r.residual_reduction = number_from(j.at("residual_reduction"));
  r.min_scaled_jacobian = number_from(j.at("min_scaled_jacobian"));
  r.inverted_cells = detail::integer_value<std::size_t>(j.at("inverted_cells"));
  r.worst_cell = detail::integer_value<mesh::CellId>(j.at("worst_cell"));
  r.max_normal_slip = number_from(j.at("max_normal_slip"));
  r.seconds = j.at("seconds").get<double>();
  r.failure = j.at("failure").get<std::string>();
  return r;
}

json timings_json(const deform::MotionTimings& t) {
  return {{"setup", t.setup},           {"assembly", t.assembly}, {"preconditioner", t.preconditioner},
          {"solve", t.solve},           {"projection", t.projection}, {"quality", t.quality},
          {"total", t.total}};
}

deform::MotionTimings timings_from_json(const json& j) {
  return {.setup = j.at("setup").get<double>(),
          .assembly = j.at("assembly").get<double>(),
          .preconditioner = j.at("preconditioner").get<double>(),
          .solve = j.at("solve").get<double>(),
          .projection = j.at("projection").get<double>(),
          .quality = j.at("quality").get<double>(),
          .total = j.at("total").get<double>()};
}

std::string local_time_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &tm);
  return text;
}

/// Projection hints per sliding node.
constexpr std::size_t kHints = std::tuple_size_v<decltype(deform::SlidingState::hints)>;

/// The hints of the sliding nodes as the file stores them: every t, every s, every face.
struct HintArrays {
  std::vector<double> t, s;
  std::vector<std::int32_t> face;
};

HintArrays hint_arrays(const std::vector<deform::SlidingState>& sliding) {
  HintArrays a;
  for (const auto& node : sliding) {
    for (const geometry::ShapeParameter& h : node.hints) {
      a.t.push_back(h.t);
      a.s.push_back(h.s);
      a.face.push_back(h.face);
    }
  }
  return a;
}

/// The hash of an array of points: the previous points that version 4 appends.
std::uint64_t points_hash(const std::vector<geometry::Vec3>& points) {
  std::uint64_t h = detail::kFnvOffset;
  detail::hash_words(h, points.data(), points.size() * sizeof(geometry::Vec3));
  return h;
}

/// The hash of a checkpoint's arrays of version 2, in file order (the hints' t only).
std::uint64_t arrays_hash(const std::vector<geometry::Vec3>& points, const std::vector<deform::SlidingState>& sliding,
                          const HintArrays& hints) {
  std::uint64_t h = points_hash(points);
  for (const auto& s : sliding) detail::hash_words(h, &s.node, sizeof s.node);
  for (const auto& s : sliding) detail::hash_words(h, &s.target, sizeof s.target);
  detail::hash_words(h, hints.t.data(), hints.t.size() * sizeof(double));
  return h;
}

/// The hash of the arrays version 3 appends: the hints' s and face.
std::uint64_t surface_hints_hash(const HintArrays& hints) {
  std::uint64_t h = detail::kFnvOffset;
  detail::hash_words(h, hints.s.data(), hints.s.size() * sizeof(double));
  detail::hash_words(h, hints.face.data(), hints.face.size() * sizeof(std::int32_t));
  return h;
}

CheckpointInfo info_from_json(const json& header) {
  CheckpointInfo info;
  info.case_file = header.at("case").get<std::string>();
  info.hotmesh_version = header.at("hotmesh_version").get<std::string>();
  info.written_at = header.at("written_at").get<std::string>();
  info.increments = detail::integer_value<int>(header.at("increments"));
  info.finished_increments = detail::integer_value<int>(header.at("finished_increments"));
  info.lambda = header.at("lambda").get<double>();
  return info;
}

/// The JSON header of a checkpoint held in `bytes` (which may be the file's beginning only);
/// checks the magic line and the format version.
json parse_header(detail::BinaryReader& in, const std::filesystem::path& path) {
  const std::string text = in.header(kMagic, "hotmesh deform writes checkpoint.hmc in its output folder");
  json header;
  try {
    header = json::parse(text);
    const int version = detail::integer_value<int>(header.at("format_version"));
    if (version < kOldestVersion || version > kVersion) {
      throw InputError::in(path.string(), fmt::format("checkpoint format {} is not one this hotmesh reads ({} to {}): "
                                                      "resume with the hotmesh that wrote it ({}), or start again",
                                                      version, kOldestVersion, kVersion,
                                                      header.value("hotmesh_version", "?")));
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError::in(path.string(), std::string("the checkpoint file's header is damaged: ") + e.what());
  }
  return header;
}

/// The beginning of a file: its magic line, header length and header.
std::string read_header_bytes(const std::filesystem::path& path) {
  require_input_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError::in(path.string(), std::string("cannot open: ") + std::strerror(errno));
  std::string bytes(kMagic.size() + sizeof(std::uint64_t), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  if (bytes.size() == kMagic.size() + sizeof(std::uint64_t) && bytes.compare(0, kMagic.size(), kMagic) == 0) {
    std::uint64_t length = 0;
    std::memcpy(&length, bytes.data() + kMagic.size(), sizeof length);
    // No more than the file holds: a damaged length must not make us reserve gigabytes.
    const std::streamoff at = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streamoff end = in.tellg();
    in.seekg(at);
    const auto available = static_cast<std::uint64_t>(std::max<std::streamoff>(end - at, 0));
    std::string header(static_cast<std::size_t>(std::min(length, available)), '\0');
    in.read(header.data(), static_cast<std::streamsize>(header.size()));
    header.resize(static_cast<std::size_t>(in.gcount()));
    bytes += header;
  }
  return bytes;
}

/// Every way the inputs of this run differ from those of the checkpoint's, one per line.
std::string input_differences(std::span<const InputFingerprint> then, std::span<const InputFingerprint> now) {
  std::string text;
  for (const InputFingerprint& a : then) {
    const auto b = std::find_if(now.begin(), now.end(), [&](const InputFingerprint& f) { return f.file == a.file; });
    if (b == now.end()) {
      text += fmt::format("\n  {} was an input of the interrupted run and is not one now", a.file.string());
    } else if (b->bytes != a.bytes || b->hash != a.hash) {
      text += fmt::format("\n  {} has changed ({} bytes then, {} now)", a.file.string(), a.bytes, b->bytes);
    }
  }
  for (const InputFingerprint& b : now) {
    const bool known = std::any_of(then.begin(), then.end(), [&](const InputFingerprint& f) { return f.file == b.file; });
    if (!known) text += fmt::format("\n  {} is a new input", b.file.string());
  }
  return text;
}

}  // namespace

std::vector<InputFingerprint> input_fingerprints(const Case& c) {
  std::vector<InputFingerprint> result;
  std::vector<char> buffer(1 << 20);
  for (const auto& file : c.inputs()) {
    require_input_file(file);
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError::in(file.string(), std::string("cannot open: ") + std::strerror(errno));
    InputFingerprint f{file, 0, detail::kFnvOffset};
    while (in) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      const auto n = static_cast<std::size_t>(in.gcount());
      detail::hash_words(f.hash, buffer.data(), n);
      f.bytes += n;
    }
    if (in.bad()) throw InputError::in(file.string(), "read error");
    result.push_back(std::move(f));
  }
  return result;
}

CheckpointOrigin checkpoint_origin(const Case& c, const mesh::Mesh& mesh, std::vector<InputFingerprint> inputs) {
  return {c.file.string(), mesh_fingerprint(mesh), std::move(inputs)};
}

namespace {

/// The checkpoint's JSON header as text. (The JSON is gone before the file is written: its
/// destructor allocates, and nothing may fail once the checkpoint is in place.)
std::string checkpoint_header(const CheckpointOrigin& origin, const deform::MotionCheckpoint& s) {
  json header{{"format_version", kVersion},
              {"hotmesh_version", HOTMESH_IO_VERSION},
              {"case", origin.case_file},
              {"written_at", local_time_now()},
              {"mesh_fingerprint", origin.mesh_fingerprint},
              {"inputs", json::array()},
              {"nodes", s.points.size()},
              {"sliding_nodes", s.sliding.size()},
              {"increments", s.increments},
              {"finished_increments", s.finished_increments},
              {"lambda", s.lambda},
              {"previous_lambda", s.previous_lambda},
              {"previous_nodes", s.previous_points.size()},
              {"split_pieces", json::array()},
              {"records", json::array()},
              {"timings", timings_json(s.timings)}};
  for (const auto& f : origin.inputs) header["inputs"].push_back({{"file", f.file.string()}, {"bytes", f.bytes}, {"hash", f.hash}});
  for (const auto& step : s.split_pieces) {
    header["split_pieces"].push_back({step.increment, step.lambda_begin, step.lambda_end, step.split_depth});
  }
  for (const auto& r : s.records) header["records"].push_back(record_json(r));
  return header.dump();
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const CheckpointOrigin& origin,
                      const deform::MotionCheckpoint& s) {
  const std::string header = checkpoint_header(origin, s);

  // Sliding nodes as arrays (ids, targets, hints' t, s and face), written without copying the points.
  const auto count = [](std::size_t n) { return static_cast<std::uint64_t>(n); };
  AtomicFile file(path);
  std::ostream& out = file.stream();
  detail::write_header(out, kMagic, header);
  detail::write_array(out, s.points);
  const auto put = [&out](const void* data, std::size_t size) { out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size)); };
  const std::uint64_t n = count(s.sliding.size()), hints = n * kHints;
  put(&n, sizeof n);
  for (const auto& node : s.sliding) put(&node.node, sizeof node.node);
  put(&n, sizeof n);
  for (const auto& node : s.sliding) put(&node.target, sizeof node.target);
  const HintArrays h = hint_arrays(s.sliding);
  put(&hints, sizeof hints);
  put(h.t.data(), h.t.size() * sizeof(double));
  const std::uint64_t hash = arrays_hash(s.points, s.sliding, h);
  put(&hash, sizeof hash);
  put(&hints, sizeof hints);
  put(h.s.data(), h.s.size() * sizeof(double));
  put(&hints, sizeof hints);
  put(h.face.data(), h.face.size() * sizeof(std::int32_t));
  const std::uint64_t surface_hash = surface_hints_hash(h);
  put(&surface_hash, sizeof surface_hash);
  detail::write_array(out, s.previous_points);
  const std::uint64_t previous_hash = points_hash(s.previous_points);
  put(&previous_hash, sizeof previous_hash);
  file.commit();
}

CheckpointInfo read_checkpoint_info(const std::filesystem::path& path) {
  const std::string bytes = read_header_bytes(path);
  detail::BinaryReader in(bytes, path, std::string(kKind));
  const json header = parse_header(in, path);
  try {
    return info_from_json(header);
  } catch (const std::exception& e) {
    throw InputError::in(path.string(), std::string("the checkpoint file's header is damaged: ") + e.what());
  }
}

namespace {

/// What the header says the arrays after it hold.
struct CheckpointCounts {
  int version = 0;
  std::uint64_t nodes = 0, sliding = 0, previous_nodes = 0;
};

/// The header's run, origin and motion state into `k`; throws what json throws when a key is
/// missing or of the wrong type.
CheckpointCounts read_header_state(const json& header, Checkpoint& k) {
  CheckpointCounts counts;
  k.info = info_from_json(header);
  counts.version = detail::integer_value<int>(header.at("format_version"));
  k.origin.case_file = k.info.case_file;
  k.origin.mesh_fingerprint = detail::integer_value<std::uint64_t>(header.at("mesh_fingerprint"));
  for (const json& f : header.at("inputs")) {
    k.origin.inputs.push_back({f.at("file").get<std::string>(), detail::integer_value<std::uint64_t>(f.at("bytes")),
                               detail::integer_value<std::uint64_t>(f.at("hash"))});
  }
  counts.nodes = detail::integer_value<std::uint64_t>(header.at("nodes"));
  counts.sliding = detail::integer_value<std::uint64_t>(header.at("sliding_nodes"));
  deform::MotionCheckpoint& s = k.state;
  s.increments = k.info.increments;
  s.finished_increments = k.info.finished_increments;
  s.lambda = k.info.lambda;
  if (counts.version >= 4) {
    s.previous_lambda = header.at("previous_lambda").get<double>();
    counts.previous_nodes = detail::integer_value<std::uint64_t>(header.at("previous_nodes"));
    if (counts.previous_nodes != 0 && counts.previous_nodes != counts.nodes) {
      throw std::runtime_error("previous_nodes is neither 0 nor nodes");
    }
  }
  // Version 1 listed the whole increments left too: they follow from finished_increments.
  // (Its run maxima, max_normal_slip and max_sliding_projection_distance, follow from the
  // records.)
  const bool listed_all = counts.version == 1;
  for (const json& step : header.at(listed_all ? "remaining" : "split_pieces")) {
    const deform::MotionStep piece{detail::integer_value<int>(step.at(0)), step.at(1).get<double>(),
                                   step.at(2).get<double>(), detail::integer_value<int>(step.at(3))};
    if (!listed_all || piece.split_depth > 0) s.split_pieces.push_back(piece);
  }
  for (const json& r : header.at("records")) s.records.push_back(record_from_json(r));
  s.timings = timings_from_json(header.at("timings"));
  return counts;
}

/// Throws unless the checkpoint was written by a run of these inputs on this mesh.
void require_same_run(const std::filesystem::path& path, const Checkpoint& k, std::uint64_t nodes,
                      const mesh::Mesh& mesh, std::span<const InputFingerprint> inputs) {
  const std::string changed = input_differences(k.origin.inputs, inputs);
  if (!changed.empty()) {
    throw InputError::in(path.string(),
                         fmt::format("cannot resume: the inputs are not those of the interrupted run (checkpoint "
                                     "written {} by case {}):{}\nA resume continues the same run, so it needs the "
                                     "same case and input files; restore them, or start the run again without "
                                     "--resume",
                                     k.info.written_at, k.info.case_file, changed));
  }
  if (k.origin.mesh_fingerprint != mesh_fingerprint(mesh) || nodes != mesh.node_count()) {
    throw InputError::in(path.string(), "cannot resume: this checkpoint was written for another mesh (case " +
                                            k.info.case_file + ")");
  }
}

/// The arrays after the header (points, sliding nodes, their hints, the previous points) into
/// k.state; whether their checksums hold.
bool read_state_arrays(detail::BinaryReader& in, const CheckpointCounts& counts, Checkpoint& k) {
  k.state.points = in.array<geometry::Vec3>(counts.nodes);
  const auto ids = in.array<mesh::NodeId>(counts.sliding);
  const auto targets = in.array<geometry::Vec3>(counts.sliding);
  HintArrays hints;
  hints.t = in.array<double>(counts.sliding * kHints);
  std::uint64_t hash = 0;
  in.read(&hash, sizeof hash);
  bool intact = true;
  if (counts.version >= 3) {
    hints.s = in.array<double>(counts.sliding * kHints);
    hints.face = in.array<std::int32_t>(counts.sliding * kHints);
    std::uint64_t surface_hash = 0;
    in.read(&surface_hash, sizeof surface_hash);
    intact = surface_hash == surface_hints_hash(hints);
  } else {  // curve parameters only
    hints.s.assign(hints.t.size(), 0.0);
    hints.face.assign(hints.t.size(), 0);
  }
  if (counts.version >= 4) {
    k.state.previous_points = in.array<geometry::Vec3>(counts.previous_nodes);
    std::uint64_t previous_hash = 0;
    in.read(&previous_hash, sizeof previous_hash);
    intact = intact && previous_hash == points_hash(k.state.previous_points);
  }
  k.state.sliding.resize(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    deform::SlidingState& node = k.state.sliding[i];
    node.node = ids[i];
    node.target = targets[i];
    for (std::size_t j = 0; j < kHints; ++j) {
      const std::size_t at = i * kHints + j;
      node.hints[j] = {hints.t[at], hints.s[at], hints.face[at]};
    }
  }
  return intact && hash == arrays_hash(k.state.points, k.state.sliding, hints);
}

}  // namespace

Checkpoint read_checkpoint(const std::filesystem::path& path, const mesh::Mesh& mesh,
                           std::span<const InputFingerprint> inputs) {
  const std::string bytes = read_file(path);
  detail::BinaryReader in(bytes, path, std::string(kKind));
  const json header = parse_header(in, path);
  Checkpoint k;
  CheckpointCounts counts;
  try {
    counts = read_header_state(header, k);
  } catch (const std::exception& e) {
    throw InputError::in(path.string(), std::string("the checkpoint file's header is damaged: ") + e.what());
  }
  require_same_run(path, k, counts.nodes, mesh, inputs);
  if (!read_state_arrays(in, counts, k) || in.at() != bytes.size()) {
    throw InputError::in(path.string(), "the checkpoint file is damaged (its content does not match its checksum)");
  }
  return k;
}

}  // namespace hotmesh::io
