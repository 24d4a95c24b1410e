// Hertz check (scripts/hertz.py, input/hertz.opts): sphere of radius 0.5 centred at the origin,
// linear tetrahedra refined near its south pole (0,0,-0.5), where it touches the block.
// Size: lc_min within r_min of the pole, growing linearly to lc at distance r_max. Units: metres.
//   gmsh -3 -setnumber lc 0.1 -setnumber lc_min 0.01 hertz_sphere.geo -o hertz_sphere.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.1, Name "Parameters/lc"]; EndIf
If (!Exists(lc_min)) lc_min = DefineNumber[0.01, Name "Parameters/lc_min"]; EndIf
If (!Exists(r_min)) r_min = DefineNumber[0.12, Name "Parameters/r_min"]; EndIf
If (!Exists(r_max)) r_max = DefineNumber[0.4, Name "Parameters/r_max"]; EndIf

Sphere(1) = {0, 0, 0, 0.5};
Field[1] = MathEval;
Field[1].F = "Sqrt(x^2 + y^2 + (z+0.5)^2)";
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
