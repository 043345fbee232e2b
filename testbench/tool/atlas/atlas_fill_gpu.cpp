// The multipass GPU filler of pst atlas (atlas_fill.h, docs/ATLAS.md, docs/MULTIPASS.md): each
// octave's noise of every texel by Hart 2001's multipass program on OpenGL ES 3 (testbench/gpu),
// the quadric, the octave sum and the colour map on the host; the same coordinate bytes through
// the CPU model, compared value for value. Without EGL at configure time (PST_HAVE_GPU unset)
// the filler refuses with "EGL: ...".
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "atlas_fill.h"
#include "input_error.h"

#ifdef PST_HAVE_GPU
#include "cpu_model.h"
#include "egl_context.h"
#include "gl_multipass.h"
#include "program.h"
#include "tables.h"
#endif

namespace pst {

#ifndef PST_HAVE_GPU

bool gpuFillerBuilt() { return false; }

GpuFill fillAtlasGpu(const Scene&, const Atlas&, const GpuFillOptions&) {
    throw InputError("EGL: this pst was built without EGL/GLESv2 (pkg-config egl glesv2 found nothing at configure "
                     "time; on Debian install libegl-dev libgles-dev, scripts/setup.sh), so --filler gpu cannot run");
}

#else

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

multipass::Variant parseVariant(const std::string& v) {
    if (v == "sgi") return multipass::Variant::Sgi;
    if (v == "rc") return multipass::Variant::Rc;
    if (v == "xor") return multipass::Variant::Xor;
    throw InputError("--variant: '" + v + "' is not sgi, rc or xor");
}

}  // namespace

bool gpuFillerBuilt() { return true; }

GpuFill fillAtlasGpu(const Scene& scene, const Atlas& atlas, const GpuFillOptions& o) {
    namespace mp = multipass;
    GpuFill r;
    r.variant = o.variant;
    r.bf = o.bf;
    const std::vector<AtlasTexel> tx = atlasTexels(atlas);
    const int H = atlas.size();
    r.image = Image(H, H, 4);
    r.texels = (long long)tx.size();

    // The texels grouped by texture (a texture's octaves are runs of the program).
    std::map<int, std::vector<const AtlasTexel*>> byTexture;
    for (const AtlasTexel& t : tx)
        byTexture[scene.objects[size_t(atlas.triangles[size_t(t.triangle)].object)].texture].push_back(&t);
    mp::Params base;
    base.variant = parseVariant(o.variant);
    base.format.bf = o.bf;
    base.seed = o.seed;
    // Refusals before any GL: the basis, the interpolation the variant can do.
    std::vector<std::string> interps;
    for (const auto& [texIndex, texels] : byTexture) {
        const Texture& tex = scene.textures[size_t(texIndex)];
        if (tex.noise.basis != NoiseBasis::Rayshade && !tex.octaves.empty())
            throw InputError("--filler gpu: texture '" + tex.name + "' has noise basis " + toString(tex.noise.basis) +
                             "; the multipass noise is a lattice value noise standing for the rayshade basis only");
        if (tex.bandlimit != Bandlimit::Off && !tex.octaves.empty())
            r.notes.push_back("texture '" + tex.name + "': bandlimit " + toString(tex.bandlimit) +
                              " ignored (the multipass octaves are point samples)");
    }

    const auto t0 = Clock::now();
    gpu::EglContext ctx = [&]() -> gpu::EglContext {
        try {
            return gpu::EglContext();
        } catch (const gpu::EglUnavailable& e) {
            throw InputError(e.what());
        }
    }();
    r.renderer = ctx.renderer();
    r.glVersion = ctx.version();
    r.eglPlatform = ctx.platform();

    for (const auto& [texIndex, texels] : byTexture) {
        const Texture& tex = scene.textures[size_t(texIndex)];
        const size_t n = texels.size();
        std::vector<double> f(n);
        for (size_t i = 0; i < n; ++i) f[i] = tex.quadric.value(texels[i]->s);
        if (!tex.octaves.empty()) {
            mp::Params params = base;
            // The scene's interpolation where the variant has it (the register combiners: linear only).
            params.interp = tex.noise.interp == NoiseInterp::Scurve && params.variant != mp::Variant::Rc
                                ? mp::Interp::Scurve : mp::Interp::Linear;
            if (tex.noise.interp == NoiseInterp::Scurve && params.variant == mp::Variant::Rc)
                r.notes.push_back("texture '" + tex.name + "': interp scurve run linear (the register-combiner "
                                  "variant interpolates linearly, section 5)");
            const std::string interp = params.interp == mp::Interp::Scurve ? "scurve" : "linear";
            if (std::find(interps.begin(), interps.end(), interp) == interps.end()) interps.push_back(interp);
            mp::Program prog;
            try {
                prog = mp::makeProgram(params);
            } catch (const std::invalid_argument& e) {
                throw InputError(std::string("--bf: ") + e.what());
            }
            const mp::Tables tables = mp::makeTables(params);
            r.b = params.format.b;
            r.drawsPerOctave = std::max(r.drawsPerOctave, prog.draws());
            // The texels as a near-square image; the padding is coordinate 0.
            const int w = std::clamp(int(std::ceil(std::sqrt(double(n)))), 1, 4096);
            const int h = int((n + size_t(w) - 1) / size_t(w));
            gpu::GlMultipass gl(w, h);
            for (const Octave& oct : tex.octaves) {
                mp::Image8 s{w, h, std::vector<uint32_t>(size_t(w) * size_t(h), 0)}, t = s, rr = s;
                for (size_t i = 0; i < n; ++i) {
                    const glm::dvec3 p = oct.M * texels[i]->s + oct.offset;
                    s.px[i] = mp::toFixed(p.x, params.format);
                    t.px[i] = mp::toFixed(p.y, params.format);
                    rr.px[i] = mp::toFixed(p.z, params.format);
                }
                gpu::Timing tm;
                const mp::Image8 noise = gl.run(prog, tables, s, t, rr, gpu::BlendArith::Shader, 1, &tm);
                r.passSeconds += tm.msPerFrame / 1e3;
                r.draws += tm.draws;
                ++r.octaves;
                const double maxv = double(params.format.max());
                for (size_t i = 0; i < n; ++i) f[i] += oct.amplitude * (double(noise.px[i]) / maxv - 0.5);
                // The CPU model on the same bytes (not timed as the fill).
                const auto tc = Clock::now();
                const mp::Image8 cpu = mp::runCpu(prog, tables, s, t, rr);
                for (size_t i = 0; i < n; ++i) r.cpuModelMismatches += cpu.px[i] != noise.px[i];
                r.noiseValues += (long long)n;
                r.cpuModelSeconds += since(tc);
            }
        }
        for (size_t i = 0; i < n; ++i) {
            const glm::dvec4 c = tex.clut.sample(f[i]);
            float* px = r.image.pixel(texels[i]->x, texels[i]->y);
            for (int k = 0; k < 4; ++k) px[k] = float(c[k]);
        }
    }
    r.seconds = since(t0) - r.cpuModelSeconds;
    for (size_t k = 0; k < interps.size(); ++k) r.interp += (k ? "," : "") + interps[k];
    if (r.interp.empty()) r.interp = "none";
    if (r.octaves == 0) r.notes.push_back("no noise octaves: nothing ran on the GPU (f is the quadric)");
    return r;
}

#endif

}  // namespace pst
