// hotmesh sample forward_step (issue 45): a 2D channel with a forward-facing step on its lower
// wall, drawn as CAD with gmsh's OpenCASCADE kernel, as a user draws it. Millimetres.
//
//   y = 10  +--------------------------- top ------------------------+
//           |                                                        |
//         inlet                        fluid                         | outlet
//           |                 ,--------------------------------------+ y = 3
//           |                 |  fillet r = 1 from (20, 2) to (21, 3)  |
//   y = 0   +-----------------+  the sharp concave foot (20, 0)      |
//           |                          metal                         |
//   y = -5  +--------------------------------------------------------+
//           x = 0             x = 20                             x = 60
//
// Two faces share the lower wall's four CAD edges: the fluid (the CFD domain) and the metal
// under it (the FEM model's part). `part` chooses which one is kept, the other is deleted:
//   part = 0, the fluid: the CAD and the CFD mesh (quads, refined towards the lower wall; gmsh
//     puts a node on every CAD vertex, the foot and the fillet's ends among them), with the
//     lower wall one patch, or (split = 1) two split at the foot:
//       gmsh -0 forward_step.geo -o forward_step.step
//       gmsh -2 -nt 1 forward_step.geo -format msh41 -o forward_step.msh
//       gmsh -2 -nt 1 -setnumber split 1 forward_step.geo -format msh41 -o forward_step-split.msh
//   part = 1, the metal: its FEM mesh for CalculiX (gmsh writes plane-stress CPS4 quads and a
//     node set per CAD curve, Line1 ... Line4 the wall, Line8 the metal's upstream end, Line9
//     its base, Line10 its downstream end; make_forward_step turns them into the plane-strain
//     deck):
//       gmsh -2 -nt 1 -setnumber part 1 forward_step.geo -format inp -o metal_gmsh.inp
// The outputs are committed as gmsh 4.8 (Debian bookworm) writes them, each written in this
// folder (the .inp names its file); a test reruns gmsh and compares. make_forward_step then
// writes the plane-strain deck and the case files.
SetFactory("OpenCASCADE");
DefineConstant[part = 0, split = 0];

L = 60;        // channel length
H = 10;        // channel height (inlet)
xs = 20;       // the step's face
hs = 3;        // the step's height
r = 1;         // the fillet's radius on the shoulder
t = 5;         // the metal's thickness under the floor

// The lower wall: floor, the step's face, the fillet, the step's top.
Point(1) = {0, 0, 0};
Point(2) = {xs, 0, 0};            // the foot: a sharp concave corner
Point(3) = {xs, hs - r, 0};       // the fillet's start (tangent to the face)
Point(4) = {xs + r, hs - r, 0};   // the fillet's centre
Point(5) = {xs + r, hs, 0};       // the fillet's end (tangent to the top)
Point(6) = {L, hs, 0};
// The fluid's other corners, and the metal's base.
Point(7) = {L, H, 0};
Point(8) = {0, H, 0};
Point(9) = {0, -t, 0};
Point(10) = {L, -t, 0};

Line(1) = {1, 2};       // floor
Line(2) = {2, 3};       // the step's face
Circle(3) = {3, 4, 5};  // the fillet
Line(4) = {5, 6};       // the step's top
Line(5) = {6, 7};       // outlet
Line(6) = {7, 8};       // top
Line(7) = {8, 1};       // inlet
Line(8) = {1, 9};       // the metal's upstream end
Line(9) = {9, 10};      // the metal's base
Line(10) = {10, 6};     // the metal's downstream end
Recursive Delete { Point{4}; }

Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};                     // the fluid
Curve Loop(2) = {8, 9, 10, -4, -3, -2, -1};
Plane Surface(2) = {2};                     // the metal

If (part == 0)
  Recursive Delete { Surface{2}; }
  If (split == 0)
    Physical Curve("wall", 1) = {1, 2, 3, 4};  // ONE sliding patch over the foot and the fillet
  Else
    Physical Curve("floor", 1) = {1};          // the wall split at the foot
    Physical Curve("step", 5) = {2, 3, 4};
  EndIf
  Physical Curve("outlet", 2) = {5};
  Physical Curve("top", 3) = {6};
  Physical Curve("inlet", 4) = {7};
  Physical Surface("fluid", 10) = {1};
  // Cells of 0.1 mm along the lower wall growing to 1 mm from 4 mm off it.
  Field[1] = Distance;
  Field[1].CurvesList = {1, 2, 3, 4};
  Field[1].NumPointsPerCurve = 400;
  Field[2] = Threshold;
  Field[2].InField = 1;
  Field[2].SizeMin = 0.1;
  Field[2].SizeMax = 1.0;
  Field[2].DistMin = 0.2;
  Field[2].DistMax = 4;
  Background Field = 2;
Else
  Recursive Delete { Surface{1}; }
  Physical Surface("METAL", 20) = {2};
  Mesh.CharacteristicLengthMax = 0.5;
  Mesh.SaveGroupsOfNodes = -1;  // a node set per curve: Line1 ... Line10 (no line elements)
EndIf

Mesh.CharacteristicLengthFromPoints = 0;
Mesh.Algorithm = 6;      // frontal-Delaunay; 8 (frontal-Delaunay for quads) crashes gmsh 4.8
Mesh.RecombineAll = 1;   // quads
