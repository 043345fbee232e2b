#include "profile.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <vector>

#include <toml++/toml.h>

#include "contract.h"
#include "input_error.h"

namespace pst {

NoiseBasis hardwareBasis(const NoiseOptions& n) {
    return n.corner == NoiseCorner::Grad12 ? NoiseBasis::Perlin2002 : NoiseBasis::Rayshade;
}

NoiseOptions hardwareNoise(const ProfileParams& p) {
    NoiseOptions n;
    n.interp = p.noiseInterp;
    n.corner = p.noiseCorner;
    n.hash = p.noiseHash;
    n.basis = hardwareBasis(n);
    n.maxPoints = p.noiseWorleyPoints;
    // A worley unit (rtl/noise/pst_worley.sv) instead of the lattice-noise unit: basis worley, the
    // hardware's search and its 256-entry feature-point ROM, Euclidean distances, no cell term.
    if (p.noiseWorleySearch != NoiseWorleySearch::None) {
        n.basis = NoiseBasis::Worley;
        n.search = p.noiseWorleySearch == NoiseWorleySearch::Octant ? WorleySearchKind::Octant : WorleySearchKind::Cube27;
        n.cubes = WorleyCubes::Rom256;
        n.metric = WorleyMetric::Euclid;
    }
    // A subband unit (rtl/noise/pst_subband.sv): basis subband on the profile's plane, the tiles
    // its ROM is sampled from (seed, size); with noise.subband_orientations K its K orientations
    // and the heuristic weights of eq. 4 (without, any orientations: the isotropic sum the ROM
    // holds does not depend on them).
    if (p.noiseSubband != NoiseSubband::None) {
        n.basis = NoiseBasis::Subband;
        n.param = p.noiseSubband == NoiseSubband::Xy   ? SubbandParam::XY
                  : p.noiseSubband == NoiseSubband::Xz ? SubbandParam::XZ
                                                       : SubbandParam::YZ;
        n.tileSize = contract::kSubbandRefTile;
        n.seed = uint32_t(contract::kSubbandSeed);
        n.orientations = p.noiseSubbandOrientations == 0 ? 4 : p.noiseSubbandOrientations;
        n.weights = SubbandWeights::Heuristic;
    }
    return n;
}
namespace {

// One key's error: recorded by Reader::fail, caught where the next key starts (parseProfile), so
// that a profile file is reported whole, every error on its own line.
struct KeyError {};

struct Reader {
    std::string path;
    const toml::table& root;
    mutable std::vector<std::string> errors;   // "FILE:LINE: FIELD: what", in file order of the checks

    [[noreturn]] void fail(const toml::node* n, const std::string& field, const std::string& what) const {
        std::string e = inputError(path, lineOf(n), field, what).what();
        if (std::find(errors.begin(), errors.end(), e) == errors.end()) errors.push_back(std::move(e));
        throw KeyError{};
    }
    // Runs one check; its error (if any) is recorded and the next check goes on.
    template <typename F>
    void each(F&& check) const {
        try {
            check();
        } catch (const KeyError&) {
        }
    }
    const toml::table& section(const char* name) const {
        const toml::node* n = root.get(name);
        if (!n || !n->is_table()) fail(n ? n : &root, name, "missing table");
        return *n->as_table();
    }
    int integer(const toml::table& t, const std::string& sec, const char* key, int lo, int hi) const {
        const toml::node* n = t.get(key);
        const std::string field = sec + "." + key;
        if (!n) fail(&t, field, "missing");
        auto v = n->as_integer();
        if (!v) fail(n, field, "expected an integer");
        if (v->get() < lo || v->get() > hi)
            fail(n, field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return int(v->get());
    }
    FixedFormat format(const toml::table& t, const char* key, int maxWidth) const {
        const std::string field = std::string("formats.") + key;
        const toml::node* n = t.get(key);
        if (!n || !n->is_table()) fail(n ? n : &t, field, "expected { int = I, frac = F }");
        FixedFormat f;
        f.intBits = integer(*n->as_table(), field, "int", contract::kFormatIntMin, contract::kFormatIntMax);
        f.fracBits = integer(*n->as_table(), field, "frac", contract::kFormatFracMin, contract::kFormatFracMax);
        if (f.width() > maxWidth) fail(n, field, "int + frac must be at most " + std::to_string(maxWidth));
        return f;
    }
};

}  // namespace

Profile parseProfile(const std::string& text, const std::string& path) {
    toml::table root;
    try {
        root = toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        throw InputError(inputWhere(path, e.source().begin.line) + ": " + std::string(e.description()));
    }
    const Reader r{path, root};
    // Every key of the schema (rtl/contract.toml, through the generated contract.h) into one
    // value array indexed by RTL parameter; enums as their index.
    namespace c = contract;
    int v[c::kNumParams] = {};
    const toml::node* where[c::kNumParams] = {};
    for (const c::KeySpec& k : c::kSchema) r.each([&] {
        const toml::table& t = r.section(k.section);
        const std::string field = std::string(k.section) + "." + k.key;
        where[k.param] = t.get(k.key);
        switch (k.kind) {
            case c::KeyKind::Range:
                v[k.param] = r.integer(t, k.section, k.key, k.lo, k.hi);
                break;
            case c::KeyKind::Values: {
                v[k.param] = r.integer(t, k.section, k.key, k.lo, k.hi);
                std::string list;
                bool ok = false;
                for (int i = 0; i < k.nValues; ++i) {
                    ok |= v[k.param] == k.values[i];
                    list += (i == 0 ? "" : i + 1 == k.nValues ? " or " : ", ") + std::to_string(k.values[i]);
                }
                if (!ok) r.fail(where[k.param], field, "must be " + list);
                break;
            }
            case c::KeyKind::Enum: {
                const toml::node* n = where[k.param];
                if (!n || !n->is_string()) r.fail(n ? n : &t, field, "expected a string");
                const std::string& s = n->as_string()->get();
                v[k.param] = -1;
                for (int i = 0; i < k.nValues; ++i)
                    if (s == k.names[i]) v[k.param] = i;
                if (v[k.param] < 0) r.fail(n, field, "unknown value '" + s + "'");
                break;
            }
            case c::KeyKind::Format: {
                const FixedFormat f = r.format(t, k.key, k.maxWidth);
                v[k.param] = f.intBits;
                v[k.param + 1] = f.fracBits;
                break;
            }
        }
    });
    // Unknown sections and keys are errors (as in scene files), so a typo does not silently
    // leave a value at what another profile had.
    for (auto&& [sec, node] : root) {
        const std::string sname(sec.str());
        bool known = false;
        for (const c::KeySpec& k : c::kSchema) known = known || sname == k.section;
        if (!known) {
            r.each([&] { r.fail(&node, sname, "unknown section"); });
            continue;
        }
        if (!node.is_table()) continue;   // reported by the key checks above ("missing table")
        for (auto&& [key, kn] : *node.as_table()) r.each([&] {
            const std::string kname(key.str());
            const c::KeySpec* spec = nullptr;
            for (const c::KeySpec& k : c::kSchema)
                if (sname == k.section && kname == k.key) spec = &k;
            if (!spec) r.fail(&kn, sname + "." + kname, "unknown key");
            if (spec->kind == c::KeyKind::Format && kn.is_table())
                for (auto&& [fk, fn] : *kn.as_table())
                    if (fk.str() != "int" && fk.str() != "frac")
                        r.fail(&fn, sname + "." + kname + "." + std::string(fk.str()), "unknown key (expected int, frac)");
        });
    }
    // The constraints between keys need every key's value: checked once every key has one.
    if (r.errors.empty())
        for (const c::Constraint& k : c::kConstraints) {
            if (k.holds(v)) continue;
            const std::string field = k.field;
            const std::string::size_type dot = field.find('.');
            const toml::node* n = root.at_path(field).node();
            r.each([&] { r.fail(n ? n : root.get(field.substr(0, dot)), field, k.message); });
        }
    if (!r.errors.empty()) {
        std::string all;
        for (const std::string& e : r.errors) all += (all.empty() ? "" : "\n") + e;
        throw InputError(all);
    }

    Profile p;
    p.path = path;
    for (int i = 0; i < c::kNumParams; ++i) c::setParam(p, c::Param(i), v[i]);
    p.noise = hardwareNoise(p);
    p.name = path.substr(path.find_last_of('/') + 1);
    if (auto dot = p.name.rfind(".toml"); dot != std::string::npos) p.name.resize(dot);
    return p;
}

Profile loadProfile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open profile");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parseProfile(ss.str(), path);
}

std::string profileDifference(const Profile& a, const Profile& b) {
    namespace c = contract;
    const auto differ = [&](int i) { return c::paramValue(a, c::Param(i)) != c::paramValue(b, c::Param(i)); };
    for (const c::KeySpec& k : c::kSchema)
        if (differ(k.param) || (k.kind == c::KeyKind::Format && differ(k.param + 1)))
            return std::string(k.section) + "." + k.key;
    return "";
}

bool isProfileFile(const std::string& nameOrPath) {
    // As scripts/pstlib/paths.py profile_path.
    const std::string ext = ".toml";
    return nameOrPath.find('/') != std::string::npos ||
           (nameOrPath.size() >= ext.size() && nameOrPath.compare(nameOrPath.size() - ext.size(), ext.size(), ext) == 0);
}

std::string profilePath(const std::string& nameOrPath, const std::string& sourceDir) {
    return isProfileFile(nameOrPath) ? nameOrPath : sourceDir + "/rtl/configs/" + nameOrPath + ".toml";
}

Profile loadNamedProfile(const std::string& nameOrPath, const std::string& sourceDir) {
    return loadProfile(profilePath(nameOrPath, sourceDir));
}

}  // namespace pst
