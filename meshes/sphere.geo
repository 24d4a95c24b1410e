// Sphere of radius r (default 0.5) centred at the origin. Unstructured linear tetrahedra. Units: metres.
//   gmsh -3 -setnumber lc 0.075 sphere.geo -o sphere.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.075, Name "Parameters/lc"]; EndIf
If (!Exists(r)) r = DefineNumber[0.5, Name "Parameters/r"]; EndIf

Sphere(1) = {0, 0, 0, r};
Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = lc;
Mesh.CharacteristicLengthFromCurvature = 0;
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1;

Physical Volume("body", 1) = {1};
Physical Surface("surface", 1) = Surface{:};
