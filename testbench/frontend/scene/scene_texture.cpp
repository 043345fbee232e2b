// Texture blocks of scene and texture files (eq. 1: quadric, octaves, noise variant, filter,
// colour map), through the scene parser's helpers (scene_parse.h).
#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "scene_parse.h"
#include "subband.h"

namespace pst::scene_detail {

namespace {
// "on" / "off" (a texture's width_cap).
bool parseOnOff(const std::string& s, bool* out) {
    if (s != "on" && s != "off") return false;
    *out = s == "on";
    return true;
}
}  // namespace

// --- Colour map: a ramp of keys [position, r, g, b(, a)] sampled into N entries ----------
ColorMap parseColorMap(const Ctx& c, const toml::table& t, const std::string& path) {
    checkKeys(c, t, path, {"size", "wrap", "interp", "ramp"});
    const int n = getInt(c, t, path, "size", 256, 1, 1 << 16);
    if (n & (n - 1)) c.fail(find(t, "size"), join(path, "size"), "must be a power of two (got " + std::to_string(n) + ")");
    WrapMode wrap = getEnum(c, t, path, "wrap", WrapMode::Mod, parseWrapMode, "mod or clamp");
    std::string interp = getString(c, t, path, "interp", "linear");
    if (interp != "linear" && interp != "step")
        c.fail(find(t, "interp"), join(path, "interp"), "unknown value '" + interp + "' (expected linear or step)");

    const toml::node* rn = find(t, "ramp");
    if (!rn) c.fail(&t, join(path, "ramp"), "missing");
    auto ra = rn->as_array();
    if (!ra || ra->empty()) c.fail(rn, join(path, "ramp"), "expected a non-empty array of [position, r, g, b(, a)]");
    std::vector<std::pair<double, glm::dvec4>> keys;
    for (size_t i = 0; i < ra->size(); ++i) {
        std::string f = join(path, "ramp") + "[" + std::to_string(i) + "]";
        auto v = asNumbers(c, *ra->get(i), f, 4, 5);
        if (v[0] < 0.0 || v[0] > 1.0) c.fail(ra->get(i), f, "position must be in [0, 1]");
        if (!keys.empty() && v[0] < keys.back().first)
            c.fail(ra->get(i), f, "positions must not decrease");
        for (size_t k = 1; k < v.size(); ++k)
            if (v[k] < 0.0 || v[k] > 1.0) c.fail(ra->get(i), f, "colour components must be in [0, 1]");
        keys.push_back({v[0], {v[1], v[2], v[3], v.size() == 5 ? v[4] : 1.0}});
    }
    if (!c.tables) return ColorMap();   // checked; the entries and SAT/MIP tables are not built
    // Entry i takes the ramp at its centre (i + 0.5) / N.
    std::vector<glm::dvec4> entries(n);
    for (int i = 0; i < n; ++i) {
        double x = (i + 0.5) / n;
        size_t k = 0;
        while (k + 1 < keys.size() && keys[k + 1].first <= x) ++k;
        if (x < keys[0].first || k + 1 == keys.size() || interp == "step") {
            entries[i] = x < keys[0].first ? keys[0].second : keys[k].second;
        } else {
            double span = keys[k + 1].first - keys[k].first;
            double a = span > 0 ? (x - keys[k].first) / span : 0.0;
            entries[i] = keys[k].second * (1.0 - a) + keys[k + 1].second * a;
        }
    }
    return ColorMap(std::move(entries), wrap);
}

// --- Texture block (eq. 1): quadric, octaves, noise variant, filter, colour map -----------
Texture parseTextureTable(const Ctx& c, const toml::table& t, const std::string& path) {
    checkKeys(c, t, path, {"quadric", "octaves", "noise", "filter", "norm", "colormap", "bandlimit", "width_cap"});
    Texture tex;
    if (const toml::node* qn = find(t, "quadric")) {
        const std::string qp = join(path, "quadric");
        auto qt = qn->as_table();
        if (!qt) c.fail(qn, qp, "expected a table of coefficients A..J (eq. 3)");
        checkKeys(c, *qt, qp, {"A", "B", "C", "D", "E", "F", "G", "H", "I", "J"});
        Quadric& q = tex.quadric;
        double* coef[] = {&q.A, &q.B, &q.C, &q.D, &q.E, &q.F, &q.G, &q.H, &q.I, &q.J};
        const char* names[] = {"A", "B", "C", "D", "E", "F", "G", "H", "I", "J"};
        for (int i = 0; i < 10; ++i) *coef[i] = getNumber(c, *qt, qp, names[i], 0.0);
    }
    if (const toml::node* on = find(t, "octaves")) {
        auto oa = on->as_array();
        if (!oa) c.fail(on, join(path, "octaves"), "expected an array of tables ([[...octaves]])");
        for (size_t i = 0; i < oa->size(); ++i) {
            std::string op = join(path, "octaves") + "[" + std::to_string(i) + "]";
            auto ot = oa->get(i)->as_table();
            if (!ot) c.fail(oa->get(i), op, "expected a table");
            checkKeys(c, *ot, op, {"amplitude", "scale", "matrix", "offset"});
            Octave o;
            o.amplitude = requireNumber(c, *ot, op, "amplitude");
            if (find(*ot, "scale") && find(*ot, "matrix"))
                c.fail(find(*ot, "matrix"), join(op, "matrix"), "give either scale or matrix, not both");
            glm::dvec3 sc = getScale(c, *ot, op, "scale");
            o.M = glm::dmat3(sc.x, 0, 0, 0, sc.y, 0, 0, 0, sc.z);
            if (const toml::node* mn = find(*ot, "matrix")) {
                // Rows as written: matrix = [[m00, m01, m02], [m10, ...], ...]; GLM is M[col][row].
                auto ma = mn->as_array();
                if (!ma || ma->size() != 3) c.fail(mn, join(op, "matrix"), "expected 3 rows of 3 numbers");
                for (int r = 0; r < 3; ++r) {
                    auto row = asNumbers(c, *ma->get(r), join(op, "matrix") + "[" + std::to_string(r) + "]", 3, 3);
                    for (int col = 0; col < 3; ++col) o.M[col][r] = row[col];
                }
            }
            o.offset = getVec3(c, *ot, op, "offset", glm::dvec3(0.0));
            tex.octaves.push_back(o);
        }
    }
    if (const toml::node* nn = find(t, "noise")) {
        const std::string np = join(path, "noise");
        auto nt = nn->as_table();
        if (!nt) c.fail(nn, np, "expected a table");
        checkKeys(c, *nt, np, {"basis", "interp", "corner", "hash", "metric", "coef", "cell", "search", "max_points", "cubes",
                               "orientations", "tile_size", "seed", "param", "weights", "sigma"});
        NoiseOptions& no = tex.noise;
        no.basis = getEnum(c, *nt, np, "basis", no.basis, parseNoiseBasis, "rayshade, perlin2002, worley or subband");
        if (const toml::node* bn = find(*nt, "basis")) tex.basisSource = c.at(bn, join(np, "basis"));
        // Each basis takes only its own keys, so a key that would be ignored is an error.
        for (const char* k : {"interp", "corner", "hash"})
            if (no.basis != NoiseBasis::Rayshade && find(*nt, k))
                c.fail(find(*nt, k), join(np, k), std::string("applies to basis rayshade only (basis is ") +
                                                      toString(no.basis) + ")");
        for (const char* k : {"metric", "coef", "cell", "search", "max_points", "cubes"})
            if (no.basis != NoiseBasis::Worley && find(*nt, k))
                c.fail(find(*nt, k), join(np, k), std::string("applies to basis worley only (basis is ") +
                                                      toString(no.basis) + ")");
        for (const char* k : {"orientations", "tile_size", "seed", "param", "weights", "sigma"})
            if (no.basis != NoiseBasis::Subband && find(*nt, k))
                c.fail(find(*nt, k), join(np, k), std::string("applies to basis subband only (basis is ") +
                                                      toString(no.basis) + ")");
        // The subband basis (model/subband.h): K orientations of eq. 1, the tiles' size.
        no.orientations = getInt(c, *nt, np, "orientations", no.orientations, 1, 64);
        if (no.orientations != 4 && no.orientations != 8)
            c.fail(find(*nt, "orientations"), join(np, "orientations"),
                   "must be 4 or 8 (got " + std::to_string(no.orientations) + ")");
        no.tileSize = getInt(c, *nt, np, "tile_size", no.tileSize, 1, 1 << 20);
        if (!subbandValidSize(no.tileSize))
            c.fail(find(*nt, "tile_size"), join(np, "tile_size"),
                   "must be a power of two in [" + std::to_string(kSubbandMinTile) + ", " +
                       std::to_string(kSubbandMaxTile) + "] (got " + std::to_string(no.tileSize) + ")");
        no.seed = uint32_t(getInt(c, *nt, np, "seed", int(no.seed), 0, 2147483647));
        no.param = getEnum(c, *nt, np, "param", no.param, parseSubbandParam, "xy, xz, yz or sphere");
        no.weights = getEnum(c, *nt, np, "weights", no.weights, parseSubbandWeights, "heuristic or least_squares");
        no.sigma = getNumber(c, *nt, np, "sigma", no.sigma);
        if (!(no.sigma > 0.0 && no.sigma <= 16.0))
            c.fail(find(*nt, "sigma"), join(np, "sigma"), "must be in (0, 16] pixels");
        no.interp = getEnum(c, *nt, np, "interp", no.interp, parseNoiseInterp, "scurve or linear");
        no.corner = getEnum(c, *nt, np, "corner", no.corner, parseNoiseCorner, "value_gradient or value");
        no.hash = getEnum(c, *nt, np, "hash", no.hash, parseNoiseHash, "rayshade or perm256");
        // quintic / grad12 / perlin256 are the hardware's names for basis perlin2002 (its unit).
        if (no.interp == NoiseInterp::Quintic || no.corner == NoiseCorner::Grad12 || no.hash == NoiseHash::Perlin256) {
            const char* k = no.interp == NoiseInterp::Quintic ? "interp" : no.corner == NoiseCorner::Grad12 ? "corner" : "hash";
            c.fail(find(*nt, k), join(np, k), "quintic, grad12 and perlin256 are basis perlin2002's noise unit: write basis = \"perlin2002\"");
        }
        no.metric = getEnum(c, *nt, np, "metric", no.metric, parseWorleyMetric, "euclid or manhattan");
        if (const toml::node* cn = find(*nt, "coef")) {
            // [C1, C2, C3, C4] of sum C_k F_k; missing trailing entries are 0.
            auto v = asNumbers(c, *cn, join(np, "coef"), 1, 4);
            no.coef = {0.0, 0.0, 0.0, 0.0};
            for (size_t k = 0; k < v.size(); ++k) no.coef[k] = v[k];
        }
        no.cell = getNumber(c, *nt, np, "cell", 0.0);
        // The worley search and feature points: the paper's (exact, 9, lcg) or a hardware unit's.
        no.search = getEnum(c, *nt, np, "search", no.search, parseWorleySearch, "exact, cube27 or octant");
        no.maxPoints = getInt(c, *nt, np, "max_points", no.maxPoints, 1, 9);
        no.cubes = getEnum(c, *nt, np, "cubes", no.cubes, parseWorleyCubes, "lcg or rom256");
        if (no.basis == NoiseBasis::Worley && no.cell == 0.0 &&
            std::all_of(no.coef.begin(), no.coef.end(), [](double x) { return x == 0.0; }))
            c.fail(find(*nt, "coef") ? find(*nt, "coef") : nn, join(np, "coef"),
                   "every coefficient and cell are 0: the basis would be constant");
    }
    tex.bandlimit = getEnum(c, t, path, "bandlimit", tex.bandlimit, parseBandlimit,
                            "off, footprint, isotropic or anisotropic");
    if (std::string why = bandlimitUnsupported(tex, tex.bandlimit); !why.empty())
        c.fail(find(t, "bandlimit"), join(path, "bandlimit"), why);
    if (const toml::node* bn = find(t, "bandlimit")) tex.bandlimitSource = c.at(bn, join(path, "bandlimit"));
    // The filter-width cap (issue 44 part 2): "on" or "off" (model/texture.h widthCapOf).
    tex.widthCap = getEnum(c, t, path, "width_cap", tex.widthCap, parseOnOff, "on or off");
    if (const toml::node* wn = find(t, "width_cap")) tex.widthCapSource = c.at(wn, join(path, "width_cap"));
    tex.filter = getEnum(c, t, path, "filter", tex.filter, parseFilterKind, "none, mip, mip_linear, sat, box or trapezoid");
    tex.norm = getEnum(c, t, path, "norm", tex.norm, parseGradNorm, "euclid, max_half_min or l1");
    tex.clut = parseColorMap(c, requireTable(c, t, path, "colormap"), join(path, "colormap"));
    {
        const toml::table& ct = requireTable(c, t, path, "colormap");
        const toml::node* sn = find(ct, "size") ? find(ct, "size") : find(t, "colormap");
        tex.clutSource = c.at(sn, join(join(path, "colormap"), "size"));
        tex.clutRamp = getString(c, ct, join(path, "colormap"), "interp", "linear") == "linear";
        const toml::node* in = find(ct, "interp") ? find(ct, "interp") : find(t, "colormap");
        tex.clutInterpSource = c.at(in, join(join(path, "colormap"), "interp"));
    }
    return tex;
}


}  // namespace pst::scene_detail
