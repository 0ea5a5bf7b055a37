// hotmesh sample stator_well: the dimensions of the meridional profile, in millimetres (z axial,
// downstream positive; r radial). The profile, the blocks and the FEM tables are built from these.
// The labelled picture is in README.md beside this file.
#pragma once

#include <array>

#include "hotmesh/core/vec2.hpp"

namespace hotmesh::samples::stator_well::dims {

// Main annulus.
inline constexpr double kZInlet = 0.0, kZOutlet = 100.0;
inline constexpr double kRHub = 420.0, kRCasing = 450.0;
// Stator: vane (the "blade", full span) over a diaphragm whose lower face, the seal land,
// carries the labyrinth seal's fins.
inline constexpr double kZStatorLipFront = 24.0, kZStatorFront = 34.0;
inline constexpr double kZStatorRear = 66.0, kZStatorLipRear = 76.0;
inline constexpr double kRLip = 410.0;        // undersides of the rotor and stator lips (rim seals)
inline constexpr double kRLand = 335.0;       // seal land, the diaphragm's lower face
inline constexpr double kStatorFillet = 4.0;  // lip underside to diaphragm face
// Rotor: two discs joined by a drum, the disc base, which runs under the seal fins.
inline constexpr double kZRotorLipFront = 20.0, kZRotorLipRear = 80.0;
inline constexpr double kZDiscFront = 12.0;   // upstream disc face, a B-spline bulging downstream by ...
inline constexpr double kDiscBulge = 1.2;     // ... this much
inline constexpr double kZDiscRear = 88.0;    // downstream disc face, bulging upstream by kDiscBulge
inline constexpr double kRDrum = 320.0;
inline constexpr double kRotorFillet = 5.0;   // lip underside to disc face
// Labyrinth seal: three trapezoidal fins hanging from the land over the disc base. A real seal
// runs at about 0.5 mm; the sample doubles the clearance so that the smallest mesh has four
// cells across it.
inline constexpr std::array<double, 3> kFinCentres{42.0, 50.0, 58.0};
inline constexpr double kFinBase = 3.0, kFinTip = 1.0;
inline constexpr double kClearance = 1.0;
inline constexpr double kRFinTip = kRDrum + kClearance;
// The joint between the upstream disc's upper and lower components: a radial gap (an axial slot
// of height kJointGap) from the disc face to z = kZJointEnd. Its end B (upper) - C (lower) is
// where the FEM deflection jumps (the paper's Fig. 16).
inline constexpr double kRJoint = 370.0, kJointGap = 1.0, kZJointEnd = 6.0;
// Thickness of the blocks that follow the walls around the fillets (block layout only).
inline constexpr double kStrip = 4.0;

/// A point (z, r) given in millimetres, in metres.
inline geometry::Vec2 at(double z_mm, double r_mm) { return {z_mm * 1e-3, r_mm * 1e-3}; }

}  // namespace hotmesh::samples::stator_well::dims
