// Cantilever beam x in [0,5], y,z in [-0.5,0.5]. Structured (transfinite) linear tetrahedra:
// n elements across each side of the 1x1 section, 5n along x, i.e. (n+1)^2 (5n+1) vertices
// and 6 * n^2 * 5n tetrahedra (each hexahedral cell split into 6 tets). Units: metres.
//   gmsh -3 -setnumber n 4 beam.geo -o beam_n4.msh
SetFactory("OpenCASCADE");
If (!Exists(n)) n = DefineNumber[4, Name "Parameters/n"]; EndIf
L = 5;

Box(1) = {0, -0.5, -0.5, L, 1, 1};
e = 1e-6;
// curves parallel to x get 5n elements, the others n
cx() = Curve In BoundingBox{-e, -0.5-e, -0.5-e, L+e, -0.5+e, -0.5+e};
cx() += Curve In BoundingBox{-e,  0.5-e, -0.5-e, L+e,  0.5+e, -0.5+e};
cx() += Curve In BoundingBox{-e, -0.5-e,  0.5-e, L+e, -0.5+e,  0.5+e};
cx() += Curve In BoundingBox{-e,  0.5-e,  0.5-e, L+e,  0.5+e,  0.5+e};
Transfinite Curve{:} = n + 1;
Transfinite Curve{cx()} = 5*n + 1;
Transfinite Surface{:};
Transfinite Volume{1};
Mesh.ElementOrder = 1;

Physical Volume("body", 1) = {1};
Physical Surface("xmin", 1) = Surface In BoundingBox{  -e, -0.5-e, -0.5-e,   e,  0.5+e,  0.5+e};
Physical Surface("xmax", 2) = Surface In BoundingBox{ L-e, -0.5-e, -0.5-e, L+e,  0.5+e,  0.5+e};
Physical Surface("ymin", 3) = Surface In BoundingBox{  -e, -0.5-e, -0.5-e, L+e, -0.5+e,  0.5+e};
Physical Surface("ymax", 4) = Surface In BoundingBox{  -e,  0.5-e, -0.5-e, L+e,  0.5+e,  0.5+e};
Physical Surface("zmin", 5) = Surface In BoundingBox{  -e, -0.5-e, -0.5-e, L+e,  0.5+e, -0.5+e};
Physical Surface("zmax", 6) = Surface In BoundingBox{  -e, -0.5-e,  0.5-e, L+e,  0.5+e,  0.5+e};
