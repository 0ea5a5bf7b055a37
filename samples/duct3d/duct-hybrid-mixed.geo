// hotmesh sample duct3d, the mixed hybrid mesh (issue 24): every 3D cell type at once. The
// floor's upstream half (x < 2h) is meshed in triangles and extruded into prism layers, as in
// duct-hybrid.geo; its downstream half in quads (recombined) and extruded into hexahedron
// layers; the core above is tetrahedra, which gmsh joins to the hexahedra's top quads with
// pyramids. As duct-hybrid.geo, gmsh meshes the FLAT duct and make_duct_hybrid lifts it onto
// the B-spline floor. Regenerate (gmsh 4.8, in samples/duct3d/):
//     gmsh -3 -format msh41 -o duct-hybrid-mixed-flat.msh duct-hybrid-mixed.geo
// then build/samples/duct3d/make_duct_hybrid samples/duct3d.
SetFactory("Built-in");

h = 10; L = 4 * h; W = 2 * h;      // mm, as duct_floor.hpp
lc_floor = 1.25;                    // the floor's triangles and quads
lc_ceiling = 2.5;                   // the core's tetrahedra under the ceiling
layers = 6; first = 0.25; growth = 1.2;

t = 0;
For i In {0 : layers - 1}
  t += first * growth^i;
  th[i] = t;
EndFor
For i In {0 : layers - 1}
  frac[i] = th[i] / t;
  ones[i] = 1;
EndFor
T = t;  // the layers' total thickness, 2.48 mm

// The floor z = 0 in two halves, split at x = L / 2.
Point(1) = {0, 0, 0, lc_floor};
Point(2) = {L / 2, 0, 0, lc_floor};
Point(3) = {L, 0, 0, lc_floor};
Point(4) = {L, W, 0, lc_floor};
Point(5) = {L / 2, W, 0, lc_floor};
Point(6) = {0, W, 0, lc_floor};
Line(1) = {1, 2};  // y = 0, upstream
Line(2) = {2, 3};  // y = 0, downstream
Line(3) = {3, 4};  // x = L
Line(4) = {4, 5};  // y = W, downstream
Line(5) = {5, 6};  // y = W, upstream
Line(6) = {6, 1};  // x = 0
Line(7) = {2, 5};  // x = L / 2, between the halves
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};   // upstream: triangles
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};   // downstream: quads
Recombine Surface{2};

// The layers over both halves (prisms over the triangles, hexahedra over the quads).
out[] = Extrude {0, 0, T} { Surface{1, 2}; Layers{ones[], frac[]}; Recombine; };
top[] = Surface In BoundingBox{-1e-6, -1e-6, T - 1e-6, L + 1e-6, W + 1e-6, T + 1e-6};

// The core, tags from 101 on.
eps = 1e-6;
Point(101) = {0, 0, h, lc_ceiling};
Point(102) = {L, 0, h, lc_ceiling};
Point(103) = {L, W, h, lc_ceiling};
Point(104) = {0, W, h, lc_ceiling};
pt1[] = Point In BoundingBox{-eps, -eps, T - eps, eps, eps, T + eps};
pt2[] = Point In BoundingBox{L - eps, -eps, T - eps, L + eps, eps, T + eps};
pt3[] = Point In BoundingBox{L - eps, W - eps, T - eps, L + eps, W + eps, T + eps};
pt4[] = Point In BoundingBox{-eps, W - eps, T - eps, eps, W + eps, T + eps};
// The top's edges: upstream (a) and downstream (b) halves on the sides.
t1a[] = Curve In BoundingBox{-eps, -eps, T - eps, L / 2 + eps, eps, T + eps};
t1b[] = Curve In BoundingBox{L / 2 - eps, -eps, T - eps, L + eps, eps, T + eps};
t2[] = Curve In BoundingBox{L - eps, -eps, T - eps, L + eps, W + eps, T + eps};
t3b[] = Curve In BoundingBox{L / 2 - eps, W - eps, T - eps, L + eps, W + eps, T + eps};
t3a[] = Curve In BoundingBox{-eps, W - eps, T - eps, L / 2 + eps, W + eps, T + eps};
t4[] = Curve In BoundingBox{-eps, -eps, T - eps, eps, W + eps, T + eps};
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
Curve Loop(132) = {t1a[0], t1b[0], 122, -111, -121};
Plane Surface(132) = {132};  // y = 0
Curve Loop(133) = {t2[0], 123, -112, -122};
Plane Surface(133) = {133};  // x = L
Curve Loop(134) = {t3b[0], t3a[0], 124, -113, -123};
Plane Surface(134) = {134};  // y = W
Curve Loop(135) = {t4[0], 121, -114, -124};
Plane Surface(135) = {135};  // x = 0
Surface Loop(140) = {top[], 131, 132, 133, 134, 135};
Volume(140) = {140};

// Patches named and tagged as the CAD faces of duct.step, found by their planes.
Physical Surface("floor", 1) = {1, 2};
Physical Surface("ceiling", 2) = {131};
Physical Surface("side_right", 3) = Surface In BoundingBox{-eps, -eps, -eps, L + eps, eps, h + eps};
Physical Surface("side_left", 4) = Surface In BoundingBox{-eps, W - eps, -eps, L + eps, W + eps, h + eps};
Physical Surface("inlet", 5) = Surface In BoundingBox{-eps, -eps, -eps, eps, W + eps, h + eps};
Physical Surface("outlet", 6) = Surface In BoundingBox{L - eps, -eps, -eps, L + eps, W + eps, h + eps};
Physical Volume("fluid", 7) = Volume{:};

Mesh.Algorithm = 6;        // frontal-Delaunay triangles (and quads, recombined)
Mesh.Algorithm3D = 1;      // Delaunay tetrahedra (pyramids on the hexahedra's top quads)
Mesh.Optimize = 1;
Mesh.MshFileVersion = 4.1;
