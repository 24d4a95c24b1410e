// Unit cube [-0.5,0.5]^3, unstructured linear tetrahedra. Units: metres.
// Parameter: lc = target element size.
//   gmsh -3 -setnumber lc 0.08 cube.geo  -> cube.msh        (~1.5k vertices)
//   gmsh -3 -setnumber lc 0.2  cube.geo  -> cube_coarse.msh (~240 vertices)
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = DefineNumber[0.08, Name "Parameters/lc"]; EndIf

Box(1) = {-0.5, -0.5, -0.5, 1, 1, 1};
Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = lc;
Mesh.ElementOrder = 1;
Mesh.Algorithm3D = 1; // Delaunay

e = 1e-6;
Physical Volume("body", 1) = {1};
Physical Surface("xmin", 1) = Surface In BoundingBox{-0.5-e, -0.5-e, -0.5-e, -0.5+e,  0.5+e,  0.5+e};
Physical Surface("xmax", 2) = Surface In BoundingBox{ 0.5-e, -0.5-e, -0.5-e,  0.5+e,  0.5+e,  0.5+e};
Physical Surface("ymin", 3) = Surface In BoundingBox{-0.5-e, -0.5-e, -0.5-e,  0.5+e, -0.5+e,  0.5+e};
Physical Surface("ymax", 4) = Surface In BoundingBox{-0.5-e,  0.5-e, -0.5-e,  0.5+e,  0.5+e,  0.5+e};
Physical Surface("zmin", 5) = Surface In BoundingBox{-0.5-e, -0.5-e, -0.5-e,  0.5+e,  0.5+e, -0.5+e};
Physical Surface("zmax", 6) = Surface In BoundingBox{-0.5-e, -0.5-e,  0.5-e,  0.5+e,  0.5+e,  0.5+e};
