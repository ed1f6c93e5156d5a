#!/usr/bin/env python3
"""The fit behind CG_SEGMENT_CENTROID_FIT (shaders/common/blocks.h): the centroid of the circular
segment of a unit disc above the chord at height u, S = (2/3) (1 - u^2)^(3/2) / (pi a), against
w = a^(2/3) for the segment's share a <= 1/2 (u in [0, 1)), least squares at each degree. Prints,
per degree, the worst error in radii and the coefficients, highest power first (as the macro's
Horner form reads them). Needs numpy."""
import numpy as np

u = np.linspace(0.0, 1.0, 200001)[:-1]
a = (np.arccos(u) - u * np.sqrt(1.0 - u * u)) / np.pi
S = (2.0 / 3.0) * (1.0 - u * u) ** 1.5 / (np.pi * a)
w = a ** (2.0 / 3.0)
for degree in range(2, 7):
    c = np.polyfit(w, S, degree)
    print(degree, "worst %.2e radii" % np.abs(np.polyval(c, w) - S).max(), " ".join("%.8f" % x for x in c))
