// Table 1 family: structured (transfinite) linear tetrahedra in a box with exactly
// nx*ny*nz vertices (3*nx*ny*nz displacement DOFs) and grid spacing d in every direction (dz in z
// if given).
// Extent: x in [-(nx-1)d/2, (nx-1)d/2], y in [-(ny-1)d/2, (ny-1)d/2], z in [0, (nz-1)dz].
// Units: metres.
//   gmsh -3 -setnumber nx 20 -setnumber ny 20 -setnumber nz 15 table1.geo -o table1_18k.msh
SetFactory("OpenCASCADE");
If (!Exists(nx)) nx = DefineNumber[20, Name "Parameters/nx"]; EndIf
If (!Exists(ny)) ny = DefineNumber[20, Name "Parameters/ny"]; EndIf
If (!Exists(nz)) nz = DefineNumber[15, Name "Parameters/nz"]; EndIf
If (!Exists(d)) d = DefineNumber[0.05, Name "Parameters/d"]; EndIf
If (!Exists(dz)) dz = d; EndIf
Lx = (nx - 1) * d;
Ly = (ny - 1) * d;
Lz = (nz - 1) * dz;
x0 = -Lx / 2; x1 = Lx / 2;
y0 = -Ly / 2; y1 = Ly / 2;
z0 = 0;       z1 = Lz;

Box(1) = {x0, y0, z0, Lx, Ly, Lz};
e = 1e-6;
cx() = Curve In BoundingBox{x0-e, y0-e, z0-e, x1+e, y0+e, z0+e};
cx() += Curve In BoundingBox{x0-e, y1-e, z0-e, x1+e, y1+e, z0+e};
cx() += Curve In BoundingBox{x0-e, y0-e, z1-e, x1+e, y0+e, z1+e};
cx() += Curve In BoundingBox{x0-e, y1-e, z1-e, x1+e, y1+e, z1+e};
cy() = Curve In BoundingBox{x0-e, y0-e, z0-e, x0+e, y1+e, z0+e};
cy() += Curve In BoundingBox{x1-e, y0-e, z0-e, x1+e, y1+e, z0+e};
cy() += Curve In BoundingBox{x0-e, y0-e, z1-e, x0+e, y1+e, z1+e};
cy() += Curve In BoundingBox{x1-e, y0-e, z1-e, x1+e, y1+e, z1+e};
cz() = Curve In BoundingBox{x0-e, y0-e, z0-e, x0+e, y0+e, z1+e};
cz() += Curve In BoundingBox{x1-e, y0-e, z0-e, x1+e, y0+e, z1+e};
cz() += Curve In BoundingBox{x0-e, y1-e, z0-e, x0+e, y1+e, z1+e};
cz() += Curve In BoundingBox{x1-e, y1-e, z0-e, x1+e, y1+e, z1+e};
Transfinite Curve{cx()} = nx;
Transfinite Curve{cy()} = ny;
Transfinite Curve{cz()} = nz;
Transfinite Surface{:};
Transfinite Volume{1};
Mesh.ElementOrder = 1;

Physical Volume("body", 1) = {1};
Physical Surface("xmin", 1) = Surface In BoundingBox{x0-e, y0-e, z0-e, x0+e, y1+e, z1+e};
Physical Surface("xmax", 2) = Surface In BoundingBox{x1-e, y0-e, z0-e, x1+e, y1+e, z1+e};
Physical Surface("ymin", 3) = Surface In BoundingBox{x0-e, y0-e, z0-e, x1+e, y0+e, z1+e};
Physical Surface("ymax", 4) = Surface In BoundingBox{x0-e, y1-e, z0-e, x1+e, y1+e, z1+e};
Physical Surface("zmin", 5) = Surface In BoundingBox{x0-e, y0-e, z0-e, x1+e, y1+e, z0+e};
Physical Surface("zmax", 6) = Surface In BoundingBox{x0-e, y0-e, z1-e, x1+e, y1+e, z1+e};
