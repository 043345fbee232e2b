#include "atlas_fill.h"

#include <chrono>
#include <map>
#include <set>

#include "driver.h"
#include "hwrender.h"
#include "scoreboard.h"

namespace pst {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void put(Image& img, int x, int y, const glm::dvec4& c) {
    float* p = img.pixel(x, y);
    for (int k = 0; k < 4; ++k) p[k] = float(c[k]);
}

}  // namespace

AtlasFill fillAtlasReference(const Scene& scene, const Atlas& atlas, int threads) {
    AtlasFill r;
    const std::vector<AtlasTexel> tx = atlasTexels(atlas);
    r.reference = Image(atlas.size(), atlas.size(), 4);
    r.texels = (long long)tx.size();
    const auto t0 = Clock::now();
    const int chunks = 256;
    parallelRows(chunks, threads, [&](int c) {
        for (size_t i = size_t(c); i < tx.size(); i += chunks) {
            const AtlasTexel& t = tx[i];
            const Texture& tex = scene.textures[size_t(scene.objects[size_t(atlas.triangles[size_t(t.triangle)].object)].texture)];
            put(r.reference, t.x, t.y, shade(tex, t.s, t.dsdu, t.dsdv).rgba);
        }
    });
    r.referenceSeconds = since(t0);
    return r;
}

AtlasFill fillAtlas(const Scene& scene, const Atlas& atlas, const Profile& p, RtlModel* rtl, size_t maxReports) {
    AtlasFill r = fillAtlasReference(scene, atlas);
    const std::vector<AtlasTexel> tx = atlasTexels(atlas);
    const int H = atlas.size();
    r.hardware = Image(H, H, 4);
    GoldenPipeline golden(p);
    Scoreboard board(p, maxReports);
    std::set<std::string> notes;
    const uint64_t cycles0 = rtl ? rtl->busyCycles() : 0;
    // One texture program per object, its texels streamed in atlas order; tag = texel index.
    std::map<int, std::vector<const AtlasTexel*>> byObject;
    for (const AtlasTexel& t : tx) byObject[atlas.triangles[size_t(t.triangle)].object].push_back(&t);
    for (const auto& [obj, texels] : byObject) {
        const Texture& tex = scene.textures[size_t(scene.objects[size_t(obj)].texture)];
        const TextureProgram prog = programTexture(p, tex);
        if (!prog.notes.empty()) notes.insert("texture '" + tex.name + "': " + prog.notes);
        for (const auto& [a, d] : prog.writes) golden.write(a, d);
        if (rtl) rtl->write(prog.writes);
        std::vector<FragmentFx> in;
        in.reserve(texels.size());
        for (const AtlasTexel* t : texels)
            in.push_back(quantizeFragment(p, uint32_t(t->y) * uint32_t(H) + uint32_t(t->x), t->s, t->dsdu, t->dsdv));
        const std::vector<PixelFx> shown =
            runBatch(golden, rtl, board, in, prog.activeOctaves, true, r.goldenSeconds, r.rtlSeconds);
        for (const PixelFx& px : shown)
            if (px.tag < uint32_t(H) * uint32_t(H)) put(r.hardware, int(px.tag % uint32_t(H)), int(px.tag / uint32_t(H)), unpackRgba(p, px.rgba));
    }
    if (rtl) {
        board.finish();
        r.passed = board.passed();
        r.mismatches = board.mismatches() + board.lost() + board.unexpected();
        r.scoreboard = board.summary();
        r.cycles = rtl->busyCycles() - cycles0;
    }
    r.notes.assign(notes.begin(), notes.end());
    return r;
}

}  // namespace pst
