// hotmesh sample duct3d, the hybrid mesh (issue 24): prism layers on the floor, tetrahedra in
// the core. Gmsh meshes the FLAT duct [0, 4h] x [0, 2h] x [0, h] (floor z = 0); make_duct_hybrid
// then lifts every node onto the B-spline floor, z -> z + f(x, y) (1 - z / h), the map duct.msh's
// hexes use, so that the floor nodes lie on the CAD floor to rounding and gmsh never needs the
// exact geometry. Regenerate (gmsh 4.8, Debian bookworm's; the committed output is its bytes):
//     gmsh -3 -format msh41 -o duct-hybrid-flat.msh duct-hybrid.geo
// in samples/duct3d/, then build/samples/duct3d/make_duct_hybrid samples/duct3d.
//
// Cells: the floor is meshed with triangles (frontal-Delaunay, size lc_floor) and extruded
// upwards by `layers` layers of prisms, the first `first` thick and each the last times
// `growth` (as duct.msh's first cells: 0.25 mm growing by 1.2); the core above is tetrahedra
// (Delaunay), from lc_floor at the layers' top to lc_ceiling at the ceiling. The layers' top is
// triangles, which the tetrahedra meet face to face, and the layers' quad sides all lie on the
// duct's sides, inlet and outlet: no pyramids are needed.
SetFactory("Built-in");

h = 10; L = 4 * h; W = 2 * h;      // mm, as duct_floor.hpp
lc_floor = 1.25;                    // the floor's triangles (duct.msh's floor: 0.83 x 1.25 mm)
lc_ceiling = 2.5;                   // the core's tetrahedra under the ceiling
layers = 6; first = 0.25; growth = 1.2;

// The layers' heights and their cumulative fractions for Extrude's Layers.
t = 0; th[] = {};
For i In {0 : layers - 1}
  t += first * growth^i;
  th[i] = t;
EndFor
For i In {0 : layers - 1}
  frac[i] = th[i] / t;
  ones[i] = 1;
EndFor
T = t;  // the layers' total thickness, 2.48 mm

// The floor z = 0: right (y = 0) and left (y = W) edges, inlet (x = 0) and outlet (x = L).
Point(1) = {0, 0, 0, lc_floor};
Point(2) = {L, 0, 0, lc_floor};
Point(3) = {L, W, 0, lc_floor};
Point(4) = {0, W, 0, lc_floor};
Line(1) = {1, 2};  // y = 0   side_right
Line(2) = {2, 3};  // x = L   outlet
Line(3) = {3, 4};  // y = W   side_left
Line(4) = {4, 1};  // x = 0   inlet
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// The prism layers (Recombine: prisms, not three tetrahedra each; quads on the sides):
// out[0] the top, out[1] the volume, out[2..5] the sides from lines 1..4.
out[] = Extrude {0, 0, T} { Surface{1}; Layers{ones[], frac[]}; Recombine; };

// The core: from the layers' top (z = T) to the ceiling (z = h). Tags from 101 on, clear of
// the entities Extrude made.
Point(101) = {0, 0, h, lc_ceiling};
Point(102) = {L, 0, h, lc_ceiling};
Point(103) = {L, W, h, lc_ceiling};
Point(104) = {0, W, h, lc_ceiling};
// The layers' top corners and edges, as Extrude made them.
eps = 1e-6;
pt1[] = Point In BoundingBox{-eps, -eps, T - eps, eps, eps, T + eps};
pt2[] = Point In BoundingBox{L - eps, -eps, T - eps, L + eps, eps, T + eps};
pt3[] = Point In BoundingBox{L - eps, W - eps, T - eps, L + eps, W + eps, T + eps};
pt4[] = Point In BoundingBox{-eps, W - eps, T - eps, eps, W + eps, T + eps};
tl1[] = Curve In BoundingBox{-eps, -eps, T - eps, L + eps, eps, T + eps};        // y = 0
tl2[] = Curve In BoundingBox{L - eps, -eps, T - eps, L + eps, W + eps, T + eps};  // x = L
tl3[] = Curve In BoundingBox{-eps, W - eps, T - eps, L + eps, W + eps, T + eps};  // y = W
tl4[] = Curve In BoundingBox{-eps, -eps, T - eps, eps, W + eps, T + eps};        // x = 0
Line(111) = {101, 102};
Line(112) = {102, 103};
Line(113) = {103, 104};
Line(114) = {104, 101};
Line(121) = {pt1[0], 101};
Line(122) = {pt2[0], 102};
Line(123) = {pt3[0], 103};
Line(124) = {pt4[0], 104};
Curve Loop(131) = {111, 112, 113, 114};
Plane Surface(131) = {131};  // the ceiling
Curve Loop(132) = {tl1[0], 122, -111, -121};
Plane Surface(132) = {132};  // y = 0
Curve Loop(133) = {tl2[0], 123, -112, -122};
Plane Surface(133) = {133};  // x = L
Curve Loop(134) = {tl3[0], 124, -113, -123};
Plane Surface(134) = {134};  // y = W
Curve Loop(135) = {tl4[0], 121, -114, -124};
Plane Surface(135) = {135};  // x = 0
Surface Loop(140) = {out[0], 131, 132, 133, 134, 135};
Volume(140) = {140};

// Patches named and tagged as the CAD faces of duct.step (duct_floor.hpp).
Physical Surface("floor", 1) = {1};
Physical Surface("ceiling", 2) = {131};
Physical Surface("side_right", 3) = {out[2], 132};
Physical Surface("side_left", 4) = {out[4], 134};
Physical Surface("inlet", 5) = {out[5], 135};
Physical Surface("outlet", 6) = {out[3], 133};
Physical Volume("fluid", 7) = {out[1], 140};

Mesh.Algorithm = 6;        // frontal-Delaunay triangles
Mesh.Algorithm3D = 1;      // Delaunay tetrahedra
Mesh.Optimize = 1;
Mesh.MshFileVersion = 4.1;
