// Notched plate for the impact demo: 80 x 30 mm, an edge notch 8 mm deep at the
// middle of the lower edge (a line crack), supports near the lower corners, the
// impact on a 4 mm segment at the middle of the upper edge. Lengths in m.
If (!Exists(lc))
  lc = 1.0e-3;
EndIf
Point(1) = {0, 0, 0, lc};
Point(2) = {0.036, 0, 0, lc};
Point(3) = {0.040, 0, 0, lc};
Point(4) = {0.044, 0, 0, lc};
Point(5) = {0.080, 0, 0, lc};
Point(6) = {0.080, 0.030, 0, lc};
Point(7) = {0.042, 0.030, 0, lc};
Point(8) = {0.038, 0.030, 0, lc};
Point(9) = {0, 0.030, 0, lc};
Point(10) = {0.040, 0.008, 0, lc};
Point(11) = {0.005, 0, 0, lc};
Point(12) = {0.075, 0, 0, lc};
Line(1) = {1, 11};
Line(2) = {11, 2};
Line(3) = {2, 3};
Line(4) = {3, 4};
Line(5) = {4, 12};
Line(6) = {12, 5};
Line(7) = {5, 6};
Line(8) = {6, 7};
Line(9) = {7, 8};
Line(10) = {8, 9};
Line(11) = {9, 1};
Line(12) = {3, 10};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
Plane Surface(1) = {1};
Curve{12} In Surface{1};
Physical Point("support_left") = {11};
Physical Point("support_right") = {12};
Physical Curve("impact") = {9};
Physical Curve("notch") = {12};
Physical Surface("glass") = {1};
