// Thick hollow sphere, inner radius a = 0.5, outer radius b = 1 (Lame's problem: docs/scenes.md).
// Unstructured linear tetrahedra. Units: metres.
//   gmsh -3 -setnumber lc 0.1 hollow_sphere.geo -o hollow_sphere.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.1, Name "Parameters/lc"]; EndIf
Sphere(1) = {0, 0, 0, 1.0};
Sphere(2) = {0, 0, 0, 0.5};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
e = 1e-3;
Physical Volume("shell", 1) = {3};
inner() = Surface In BoundingBox{-0.5-e, -0.5-e, -0.5-e, 0.5+e, 0.5+e, 0.5+e};
outer() = Surface In BoundingBox{-1-e, -1-e, -1-e, 1+e, 1+e, 1+e};
outer() -= inner();
Physical Surface("inner", 1) = {inner()};
Physical Surface("outer", 2) = {outer()};
