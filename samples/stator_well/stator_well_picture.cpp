// hotmesh sample stator_well: labelled pictures of the meridional profile for the README.
//
// Run:   build/samples/stator_well/stator_well_picture [OUTPUT_FOLDER]   (default: current folder)
// Writes stator_well-profile.png: the profile's curves coloured by their role in case_small.yaml
// (the paper's Fig. 12-b: green fixed, red passive, grey prescribed; blue sliding), each patch
// named, the CAD face numbers beside their curves; and stator_well-seal.png and
// stator_well-joint.png: close-ups with the FEM nodes and their deflections (amplified 3 times),
// the joint's points B and C.
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "dimensions.hpp"
#include "fem_tables.hpp"
#include "hotmesh/io/figure.hpp"
#include "stator_well.hpp"

namespace {

using namespace hotmesh::samples::stator_well;
namespace io = hotmesh::io;

constexpr double kMm = 1e3;  // pictures in millimetres

io::Color role_colour(Patch p) {
  switch (p) {
    case Patch::casing:
    case Patch::blade: return io::colors::green;
    case Patch::inlet:
    case Patch::outlet:
    case Patch::stator_outer: return io::colors::red;
    case Patch::disc_up_upper:
    case Patch::disc_up_lower:
    case Patch::disc_base:
    case Patch::disc_down: return io::colors::blue;
    default: return io::colors::grey;
  }
}

std::vector<io::PlotPoint> sampled(const hotmesh::samples::BSplineCurve2d& c) {
  std::vector<io::PlotPoint> points;
  for (int i = 0; i <= 64; ++i) {
    const auto p = c.point(c.first_parameter() + (c.last_parameter() - c.first_parameter()) * i / 64);
    points.push_back({p.x * kMm, p.y * kMm});
  }
  return points;
}

/// Where each patch's name goes (mm), chosen by hand so the labels stay clear of each other.
const std::map<Patch, io::PlotPoint> kLabels{
    {Patch::inlet, {-16, 436}},        {Patch::outlet, {102, 436}},       {Patch::casing, {40, 454}},
    {Patch::blade, {40, 436}},         {Patch::stator_outer, {18, 425}},  {Patch::stator_front, {36, 392}},
    {Patch::fins, {44, 340}},          {Patch::stator_rear, {47, 380}},   {Patch::rim_up, {-16, 414}},
    {Patch::disc_up_upper, {-26, 394}}, {Patch::joint, {-10, 366}},       {Patch::disc_up_lower, {-26, 345}},
    {Patch::disc_base, {44, 312}},     {Patch::disc_down, {92, 360}},     {Patch::rim_down, {84, 414}}};

void profile_picture(const std::vector<ProfileCurve>& loop, const std::filesystem::path& file) {
  io::Figure f({.width = 1300, .height = 1300, .title = "stator_well: meridional profile, patches and CAD faces",
                .x_label = "z (mm)", .y_label = "r (mm)"});
  const auto order = cad_face_order(loop);
  for (std::size_t id = 1; id <= order.size(); ++id) {
    const ProfileCurve& c = loop[static_cast<std::size_t>(order[id - 1])];
    const auto pts = sampled(c.curve);
    f.polyline(pts, {role_colour(c.patch), 3.0});
    const auto& mid = pts[pts.size() / 2];
    f.text({mid.x + 0.6, mid.y + 0.6}, std::to_string(id), 11.0, io::colors::black);
  }
  for (const auto& [patch, at] : kLabels) f.text(at, std::string(name(patch)), 15.0, role_colour(patch));
  f.legend("fixed", {io::colors::green, 3.0});
  f.legend("passive", {io::colors::red, 3.0});
  f.legend("prescribed", {io::colors::grey, 3.0});
  f.legend("sliding (case_small)", {io::colors::blue, 3.0});
  f.set_view(-30, 115, 300, 460);
  f.save(file);
}

void close_up(const std::vector<ProfileCurve>& loop, const std::vector<FemTable>& tables, const std::filesystem::path& file,
              const std::string& title, std::array<double, 4> view) {
  constexpr double kAmplify = 3.0;
  io::Figure f({.width = 1400, .height = 900, .title = title, .x_label = "z (mm)", .y_label = "r (mm)"});
  for (const ProfileCurve& c : loop) f.polyline(sampled(c.curve), {role_colour(c.patch), 2.5});
  for (const FemTable& t : tables) {
    for (const FemNode& n : t.nodes) {
      const io::PlotPoint at{n.zr.x * kMm, n.zr.y * kMm};
      f.arrow(at, {at.x + kAmplify * n.dzr.x * kMm, at.y + kAmplify * n.dzr.y * kMm}, {io::colors::orange, 1.5}, 7.0);
      f.marker(at, io::colors::black, 3.0);
    }
  }
  using namespace dims;
  f.text({kZJointEnd - 0.9, kRJoint + kJointGap + 0.15}, "B", 16.0);
  f.text({kZJointEnd - 0.9, kRJoint - 0.55}, "C", 16.0);
  f.legend("FEM nodes", {io::colors::black, 3.0}, true);
  f.legend(fmt::format("FEM deflection x {:.0f}", kAmplify), {io::colors::orange, 1.5});
  f.set_view(view[0], view[1], view[2], view[3]);
  f.save(file);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    std::filesystem::create_directories(folder);
    const auto loop = profile();
    const auto tables = fem_tables(loop);
    profile_picture(loop, folder / "stator_well-profile.png");
    close_up(loop, tables, folder / "stator_well-seal.png", "stator_well: the labyrinth seal and its FEM deflections",
             {30, 70, 312, 342});
    close_up(loop, tables, folder / "stator_well-joint.png",
             "stator_well: the joint between the upper and lower disc components", {0, 24, 362, 378});
    std::printf("wrote stator_well-profile.png, stator_well-seal.png, stator_well-joint.png to %s\n", folder.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stator_well_picture: %s\n", e.what());
    return 1;
  }
}
