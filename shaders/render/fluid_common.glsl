// Shared by the fluid-surface passes: the per-pixel planes of one storage buffer (each
// width x height words) that the particles are splatted into and the surface is shaded from.
const uint kNearest = 0u;   // view depth of the nearest sphere point (float bits; atomicMin)
const uint kSmoothed = 1u;  // that depth after the bilateral filter (float)
const uint kThickness = 2u; // sum of sphere chords, in 1/256 sphere radii (atomicAdd)
const uint kRed = 3u, kGreen = 4u, kBlue = 5u;  // colour-map colours x chord x 255
const uint kWeight = 6u;    // chord x 255: divides the colour sums
const uint kAcross = 7u;    // the depth after the filter's first pass
const uint kPlanes = 8u;
// An empty pixel's depth: the largest finite float, so atomicMin on its bits finds the nearest.
const float kEmpty = 3.0e38;
