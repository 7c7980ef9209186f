// Borden et al. (2012) branching plate: 100 x 40 mm, notch from the left edge at
// mid-height to x = 50 mm (a line crack), lengths in m.
If (!Exists(lc))
  lc = 1.0e-3;
EndIf
Point(1) = {0, 0, 0, lc};
Point(2) = {0.1, 0, 0, lc};
Point(3) = {0.1, 0.04, 0, lc};
Point(4) = {0, 0.04, 0, lc};
Point(5) = {0, 0.02, 0, lc};
Point(6) = {0.05, 0.02, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Line(6) = {5, 6};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Curve{6} In Surface{1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Curve("notch") = {6};
Physical Surface("glass") = {1};
