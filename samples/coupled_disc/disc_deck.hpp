// hotmesh sample coupled_disc: an axisymmetric CalculiX model of the stator well's rotor
// (samples/stator_well), written from the same profile as the CFD sector.
//
// The model is a band of metal under every rotor wall of the CFD sector, in the profile's
// order: the upstream blade platform and lip (rim_up), the upstream disc's upper face
// (disc_up_upper), around the joint's slot (joint), the disc's lower face (disc_up_lower),
// the drum under the seal fins (disc_base), the downstream disc's face, fillet and lip
// (disc_down) and the downstream lip and platform (rim_down). Its wall nodes are the stator
// well's FEM nodes (fem_tables.hpp: on the walls' curves, at most 5 mm apart); `layers` rows
// of CAX4 elements go `thickness` into the metal along the wall's normal. It is not a whole
// rotor (a thin shell of steel, not discs): the sample shows the loop, and a band whose
// wetted side is the CFD walls is the smallest model that gives all of them from one solve.
//
// Loads: nodal temperatures varying linearly in r from `bore_temperature` (r = 0.31 m) to
// `rim_temperature` (r = 0.42 m), from 20 degrees; centrifugal (*DLOAD CENTRIF, omega^2 about
// the z axis, CalculiX's y); the bore (the drum's inner face) held axially at `axial_shift`
// (the shaft carries the rotor downstream), free radially.
#pragma once

#include <string>
#include <vector>

#include "stator_well.hpp"

namespace hotmesh::samples::coupled_disc {

/// One coupling iteration's thermal and mechanical load of the disc.
struct DiscLoad {
  double bore_temperature = 120.0;  ///< degrees C at r = 0.31 m
  double rim_temperature = 160.0;   ///< degrees C at r = 0.42 m
  double omega_squared = 1.0e5;     ///< (rad/s)^2, about 3000 rpm
  double axial_shift = 1.0e-3;      ///< m, the bore's axial position
};

struct Band {
  double thickness = 2.5e-3;  ///< m, into the metal: less than the FEM nodes' spacing at the
                              ///< metal's convex corners (rim lips, the joint's mouth)
  int layers = 2;
};

/// The rotor walls of the CFD case the band lies under, in the order of the profile's loop.
inline constexpr stator_well::Patch kRotorWalls[] = {
    stator_well::Patch::rim_up,        stator_well::Patch::disc_up_upper, stator_well::Patch::joint,
    stator_well::Patch::disc_up_lower, stator_well::Patch::disc_base,     stator_well::Patch::disc_down,
    stator_well::Patch::rim_down};

/// The element surface of the deck under a wall: the patch's name in upper case ("DISC_BASE").
std::string deck_set(stator_well::Patch patch);

/// The mesh part of the deck (*NODE, *ELEMENT, the surfaces of the walls, NSET BORE), for
/// an *INCLUDE.
std::string disc_mesh_deck(const std::vector<stator_well::ProfileCurve>& loop, const Band& band = {});

/// The deck of one iteration: heading, *INCLUDE of `mesh_file`, steel, and one static step
/// with `load`, writing U and NT to the .frd (ASCII).
std::string disc_deck(const std::vector<stator_well::ProfileCurve>& loop, const std::string& mesh_file,
                      const DiscLoad& load, const std::string& title, const Band& band = {});

}  // namespace hotmesh::samples::coupled_disc
