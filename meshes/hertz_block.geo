// Hertz check (scripts/hertz.py, input/hertz.opts): block [-0.6,0.6]^2 x [-0.6,0] whose top face
// (z = 0) is touched by the sphere at its centre; linear tetrahedra refined near (0,0,0):
// lc_min within r_min of that point, growing linearly to lc at distance r_max. Units: metres.
//   gmsh -3 -setnumber lc 0.15 -setnumber lc_min 0.01 hertz_block.geo -o hertz_block.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.15, Name "Parameters/lc"]; EndIf
If (!Exists(lc_min)) lc_min = DefineNumber[0.01, Name "Parameters/lc_min"]; EndIf
If (!Exists(r_min)) r_min = DefineNumber[0.12, Name "Parameters/r_min"]; EndIf
If (!Exists(r_max)) r_max = DefineNumber[0.4, Name "Parameters/r_max"]; EndIf

Box(1) = {-0.6, -0.6, -0.6, 1.2, 1.2, 0.6};
Field[1] = MathEval;
Field[1].F = "Sqrt(x^2 + y^2 + z^2)";
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = lc_min;
Field[2].SizeMax = lc;
Field[2].DistMin = r_min;
Field[2].DistMax = r_max;
Background Field = 2;

Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1;

Physical Volume("body", 1) = {1};
Physical Surface("surface", 1) = Surface{:};
