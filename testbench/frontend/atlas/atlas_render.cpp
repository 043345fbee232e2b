#include "atlas_render.h"

#include <algorithm>
#include <cmath>

#include "multires.h"

namespace pst {
namespace {

// Per object, its triangles unshared, carrying (u, v, triangle) as texture coordinates: the
// rasterizer's perspective-correct interpolation then gives the chart point, and the
// constant third coordinate names the triangle.
FragmentBuffer rasterizeCharts(const Scene& scene, const Atlas& atlas) {
    std::vector<Mesh> meshes(scene.objects.size());
    for (size_t t = 0; t < atlas.triangles.size(); ++t) {
        const AtlasTriangle& tri = atlas.triangles[t];
        Mesh& m = meshes[size_t(tri.object)];
        const uint32_t base = uint32_t(m.positions.size());
        for (int k = 0; k < 3; ++k) {
            m.positions.push_back(tri.x[size_t(k)]);
            m.texcoords.push_back(glm::dvec3(atlas.charts[t].u[size_t(k)], double(t)));
        }
        m.triangles.push_back({base, base + 1, base + 2});
    }
    FragmentBuffer fb(scene.camera.width, scene.camera.height);
    for (size_t o = 0; o < meshes.size(); ++o)
        if (scene.objects[o].layer == 0 && !meshes[o].triangles.empty())
            rasterize(scene.camera, meshes[o], int(o), fb);
    return fb;
}

void fill(Image& img, const glm::dvec4& c) {
    for (size_t i = 0; i < img.data.size(); i += 4)
        for (int k = 0; k < 4; ++k) img.data[i + size_t(k)] = float(c[k]);
}

inline void over(float* dst, const glm::dvec4& src) {
    const double a = std::clamp(src.a, 0.0, 1.0);
    for (int c = 0; c < 3; ++c) dst[c] = float(src[c] * a + dst[c] * (1.0 - a));
    dst[3] = float(a + dst[3] * (1.0 - a));
}

}  // namespace

std::vector<AtlasTriangle> sceneTriangles(const Scene& scene, size_t* skipped) {
    std::vector<AtlasTriangle> out;
    if (skipped) *skipped = 0;
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        const SceneObject& obj = scene.objects[o];
        if (obj.layer != 0) continue;
        for (size_t i = 0; i < obj.mesh.triangles.size(); ++i) {
            const auto& tr = obj.mesh.triangles[i];
            // A zero-area triangle has no chart (mesh.h: zeroArea, the rule shared with render).
            if (zeroArea(obj.mesh.positions[tr[0]], obj.mesh.positions[tr[1]], obj.mesh.positions[tr[2]])) {
                if (skipped) ++*skipped;
                continue;
            }
            AtlasTriangle t;
            t.object = int(o);
            t.index = int(i);
            for (int k = 0; k < 3; ++k) {
                t.x[size_t(k)] = obj.mesh.positions[tr[size_t(k)]];
                t.s[size_t(k)] = obj.mesh.texcoords[tr[size_t(k)]];
            }
            out.push_back(t);
        }
    }
    return out;
}

Scene opaqueLayer(const Scene& scene) {
    Scene s = scene;
    s.objects.clear();
    for (const SceneObject& o : scene.objects)
        if (o.layer == 0) s.objects.push_back(o);
    return s;
}

namespace {

// The view drawn by texture mapping: every covered screen pixel takes lookup(fragment), an
// AtlasLookup (its colour, whether it read a background or another triangle's texel).
template <class Lookup>
AtlasRender drawWithAtlas(const Scene& scene, const Atlas& atlas, Lookup lookup) {
    const FragmentBuffer fb = rasterizeCharts(scene, atlas);
    AtlasRender r;
    r.image = Image(fb.width(), fb.height(), 4);
    fill(r.image, scene.background);
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x) {
            const Fragment& f = fb.at(x, y);
            if (f.object < 0) continue;
            const AtlasLookup l = lookup(f);
            over(r.image.pixel(x, y), l.rgba);
            ++r.pixels;
            r.seamPixels += l.touchedForeign;
        }
    return r;
}

}  // namespace

AtlasRender renderWithAtlas(const Scene& scene, const Atlas& atlas, const Image& texels,
                            const std::vector<int>& owners, Magnification filter) {
    return drawWithAtlas(scene, atlas, [&](const Fragment& f) {
        return lookupAtlas(texels.data, owners, atlas.size(), int(std::lround(f.s.z)), glm::dvec2(f.s), filter);
    });
}

AtlasRender renderWithAtlasTrilinear(const Scene& scene, const Atlas& atlas, const std::vector<Image>& levels) {
    return drawWithAtlas(scene, atlas, [&](const Fragment& f) {
        return AtlasLookup{lookupTrilinear(levels, glm::dvec2(f.s), glm::dvec2(f.dsdx), glm::dvec2(f.dsdy)), false};
    });
}

Image relativeScalePicture(const Scene& scene, const Atlas& atlas) {
    const FragmentBuffer fb = rasterizeCharts(scene, atlas);
    const std::vector<double> r = triangleScales(atlas);
    Image img(fb.width(), fb.height(), 4);
    fill(img, glm::dvec4(0.0, 0.0, 0.0, 1.0));
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x) {
            const Fragment& f = fb.at(x, y);
            if (f.object < 0) continue;
            // lg r / 2 in [-1, 1]: -1 blue, 0 green, +1 red.
            const double e = std::clamp(std::log2(r[size_t(std::lround(f.s.z))]) / 2.0, -1.0, 1.0);
            float* p = img.pixel(x, y);
            p[0] = float(std::max(0.0, e));
            p[1] = float(1.0 - std::abs(e));
            p[2] = float(std::max(0.0, -e));
            p[3] = 1.f;
        }
    return img;
}

}  // namespace pst
