// Kalthoff-Winkler plate, upper half (symmetry about y = 0): 100 x 100 mm, the edge
// notch from the left edge at y = 25 mm to x = 50 mm (a line crack), the impact on
// the left edge below the notch. Lengths in m.
If (!Exists(lc))
  lc = 1.0e-3;
EndIf
Point(1) = {0, 0, 0, lc};
Point(2) = {0.1, 0, 0, lc};
Point(3) = {0.1, 0.1, 0, lc};
Point(4) = {0, 0.1, 0, lc};
Point(5) = {0, 0.025, 0, lc};
Point(6) = {0.05, 0.025, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Line(6) = {5, 6};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Curve{6} In Surface{1};
Physical Curve("symmetry") = {1};
Physical Curve("impact") = {5};
Physical Curve("notch") = {6};
Physical Surface("steel") = {1};
