#include "profile.h"

#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "input_error.h"

namespace pst {
namespace {

struct Reader {
    std::string path;
    const toml::table& root;

    [[noreturn]] void fail(const toml::node* n, const std::string& field, const std::string& what) const {
        std::ostringstream os;
        os << path;
        if (n && n->source().begin.line > 0) os << ":" << n->source().begin.line;
        os << ": " << field << ": " << what;
        throw InputError(os.str());
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
    template <typename E>
    E choice(const toml::table& t, const std::string& sec, const char* key,
             bool (*parse)(const std::string&, E*)) const {
        const toml::node* n = t.get(key);
        const std::string field = sec + "." + key;
        if (!n || !n->is_string()) fail(n ? n : &t, field, "expected a string");
        E e;
        if (!parse(n->as_string()->get(), &e)) fail(n, field, "unknown value '" + n->as_string()->get() + "'");
        return e;
    }
    FixedFormat format(const toml::table& t, const char* key, int maxWidth) const {
        const std::string field = std::string("formats.") + key;
        const toml::node* n = t.get(key);
        if (!n || !n->is_table()) fail(n ? n : &t, field, "expected { int = I, frac = F }");
        FixedFormat f;
        f.intBits = integer(*n->as_table(), field, "int", 1, 62);
        f.fracBits = integer(*n->as_table(), field, "frac", 0, 62);
        if (f.width() > maxWidth) fail(n, field, "int + frac must be at most " + std::to_string(maxWidth));
        return f;
    }
};

}  // namespace

bool parseDatapath(const std::string& s, Datapath* d) {
    if (s == "parallel") *d = Datapath::Parallel;
    else if (s == "serial") *d = Datapath::Serial;
    else return false;
    return true;
}

Profile parseProfile(const std::string& text, const std::string& path) {
    toml::table root;
    try {
        root = toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        throw InputError(path + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
    }
    const Reader r{path, root};
    Profile p;
    p.path = path;
    const auto& pipe = r.section("pipeline");
    p.octaves = r.integer(pipe, "pipeline", "octaves", 1, 16);
    p.noiseUnits = r.integer(pipe, "pipeline", "noise_units", 1, 16);
    if (p.octaves % p.noiseUnits != 0)
        r.fail(pipe.get("noise_units"), "pipeline.noise_units", "must divide pipeline.octaves");
    p.noiseSteps = r.integer(pipe, "pipeline", "noise_steps", 1, 8);
    if (p.noiseSteps != 1 && p.noiseSteps != 2 && p.noiseSteps != 4 && p.noiseSteps != 8)
        r.fail(pipe.get("noise_steps"), "pipeline.noise_steps", "must be 1, 2, 4 or 8");
    p.log2Clut = r.integer(pipe, "pipeline", "log2_clut", 1, 11);  // the SAT range (0x2000 + 4e) must stay below 0x4000
    p.colourBits = r.integer(pipe, "pipeline", "colour_bits", 1, 8);
    p.datapath = r.choice(pipe, "pipeline", "datapath", parseDatapath);
    if (p.datapath == Datapath::Serial && p.noiseSteps < 4)
        r.fail(pipe.get("datapath"), "pipeline.datapath", "serial needs pipeline.noise_steps >= 4");
    const auto& noise = r.section("noise");
    p.noise.interp = r.choice(noise, "noise", "interp", parseNoiseInterp);
    p.noise.corner = r.choice(noise, "noise", "corner", parseNoiseCorner);
    p.noise.hash = r.choice(noise, "noise", "hash", parseNoiseHash);
    p.noiseValueFrac = r.integer(noise, "noise", "value_frac", 1, 15);
    p.noiseLatticeFrac = r.integer(noise, "noise", "lattice_frac", 1, 20);
    p.noiseOutFrac = r.integer(noise, "noise", "out_frac", 1, 24);
    p.noiseGuardBits = r.integer(noise, "noise", "guard_bits", 1, 8);
    const auto& filt = r.section("filter");
    p.filterNorm = r.choice(filt, "filter", "norm", parseGradNorm);
    p.filterRecipFrac = r.integer(filt, "filter", "recip_frac", 4, 24);
    const auto& fm = r.section("formats");
    // Register formats are written through the 32-bit register port: at most 32 bits.
    p.coord = r.format(fm, "coord", 40);
    p.jacobian = r.format(fm, "jacobian", 40);
    p.matrix = r.format(fm, "matrix", 32);
    p.offset = r.format(fm, "offset", 32);
    p.amplitude = r.format(fm, "amplitude", 32);
    p.gradMatrix = r.format(fm, "grad_matrix", 32);
    p.quadric = r.format(fm, "quadric", 32);
    p.f = r.format(fm, "f", 48);
    p.grad = r.format(fm, "grad", 48);
    p.widthFrac = r.integer(fm, "formats", "width_frac", 0, 24);
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

std::string profilePath(const std::string& nameOrPath, const std::string& sourceDir) {
    if (nameOrPath.find('/') != std::string::npos || nameOrPath.find(".toml") != std::string::npos)
        return nameOrPath;
    return sourceDir + "/rtl/configs/" + nameOrPath + ".toml";
}

}  // namespace pst
