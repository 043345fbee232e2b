// The atlas mode around a scene: the scene's surface triangles, the object drawn by texture
// mapping the filled atlas (nearest or bilinear magnification), the seams counted, and the
// per-triangle relative-scale picture of Fig. 7.
#pragma once

#include <vector>

#include "atlas.h"
#include "render.h"
#include "scene.h"

namespace pst {

// The triangles of the scene's layer-0 objects (world positions, texture-space s). A zero-area
// triangle (mesh.h: zeroArea, the rule render follows too) has no surface and gets no chart: it
// is skipped, and counted in *skipped when given. Its index (AtlasTriangle::index) stays its
// index in the object's mesh.
std::vector<AtlasTriangle> sceneTriangles(const Scene& scene, size_t* skipped = nullptr);

// The scene with its layer-0 objects only (what the atlas covers).
Scene opaqueLayer(const Scene& scene);

struct AtlasRender {
    Image image;                 // RGBA
    long long pixels = 0;        // covered screen pixels
    long long seamPixels = 0;    // pixels whose lookup read a background or foreign texel
};

// Draws the scene's layer-0 objects from its camera with the atlas as their texture:
// perspective-correct chart coordinates per pixel centre, then the lookup.
// `texels`: the filled atlas, size x size RGBA.
AtlasRender renderWithAtlas(const Scene& scene, const Atlas& atlas, const Image& texels,
                            const std::vector<int>& owners, Magnification filter);

// The same with trilinear lookups in the MIP levels of the filled atlas (multires.h: mipLevels),
// the level from the screen derivatives of the chart point.
AtlasRender renderWithAtlasTrilinear(const Scene& scene, const Atlas& atlas, const std::vector<Image>& levels);

// Fig. 7: the scene's view with each triangle coloured by its relative scale r: green at r = 1,
// toward blue for r < 1 (too few samples) and red for r > 1 (too many), saturating at a factor 4.
Image relativeScalePicture(const Scene& scene, const Atlas& atlas);

}  // namespace pst
