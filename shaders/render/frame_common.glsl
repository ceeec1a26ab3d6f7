// Shared by the render pipelines: the colour-map lookup.

// 256 colours of the map (binding given by the includer) at t in [0, 1].
#define COLORMAP_LOOKUP(table, t) (table[int(clamp(t, 0.0, 1.0) * 255.0 + 0.5)].rgb)
