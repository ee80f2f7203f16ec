// A stenosis for data/vessels/stenosis.toml (scripts/make_gallery_vessels.py writes the STEP):
// a solid tube of diameter 3.5 along z from 0 to 10, narrowed to 2.1 by a cosine bump of length 4 at
// z = 5, revolved about the axis x = y = 2.5 by OpenCASCADE. The profile is a spline through
// 41 points of the radius r(z) = 1.75 - 0.35 (1 + cos(pi (z - 5) / 2)) for |z - 5| < 2.
SetFactory("OpenCASCADE");
R = 1.75; depth = 0.7; half = 2.0; L = 10.0; cx = 2.5; cy = 2.5;
p0 = newp; Point(p0) = {cx + R, cy, 0};
p1 = newp; Point(p1) = {cx + R, cy, 5 - half};
pts[] = {p1};
For i In {1:39}
  z = 5 - half + 2 * half * i / 40;
  r = R - 0.5 * depth * (1 + Cos(Pi * (z - 5) / half));
  p = newp; Point(p) = {cx + r, cy, z};
  pts[] += {p};
EndFor
p2 = newp; Point(p2) = {cx + R, cy, 5 + half};
pts[] += {p2};
p3 = newp; Point(p3) = {cx + R, cy, L};
a0 = newp; Point(a0) = {cx, cy, 0};
a1 = newp; Point(a1) = {cx, cy, L};
l0 = newl; Line(l0) = {p0, p1};
l1 = newl; Spline(l1) = pts[];
l2 = newl; Line(l2) = {p2, p3};
l3 = newl; Line(l3) = {p3, a1};
l4 = newl; Line(l4) = {a1, a0};
l5 = newl; Line(l5) = {a0, p0};
Curve Loop(1) = {l0, l1, l2, l3, l4, l5};
Plane Surface(1) = {1};
// A solid: its end caps in the box faces are dropped on import, its wall faces share edges.
Extrude {{0, 0, 1}, {cx, cy, 0}, 2 * Pi} { Surface{1}; }
