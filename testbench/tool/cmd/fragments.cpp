// pst fragments SCENE: the rasterizer's fragment stream of one layer as a fragment file.
#include <iostream>
#include <memory>
#include <sstream>

#include "common.h"
#include "fragments.h"
#include "imageio.h"

namespace pst::cli {
namespace {

struct FragArgs {
    std::string scene, out;
    int size = 0, layer = 0;
    bool quiet = false;
};

int runFragments(const FragArgs& a) {
    Scene scene = loadScene(a.scene, a.size, a.size);
    if (a.layer < 0 || a.layer >= scene.layers())
        throw InputError("--layer: scene has layers 0.." + std::to_string(scene.layers() - 1));
    std::vector<FragmentRecord> recs;
    for (const auto& f : sceneFragments(scene, a.layer)) recs.push_back({f.s, f.dsdx, f.dsdy});
    std::ostringstream os;
    writeFragments(os, recs);
    if (a.out.empty() || a.out == "-") std::cout << os.str();
    else {
        Outputs outputs;   // the whole file, or none
        writeTextFile(outputs.file("-o", a.out), os.str());
        outputs.commit();
    }
    return 0;
}

}  // namespace

Command registerFragments(CLI::App& app) {
    auto a = std::make_shared<FragArgs>();
    auto* frag = app.add_subcommand("fragments", "Write a scene's fragment stream as a fragment file");
    frag->add_option("scene", a->scene, "Scene file")->required()->check(CLI::ExistingFile);
    frag->add_option("--size", a->size, "Square image size, overrides the scene's (0: the scene's)")->check(CLI::Range(1, 16384));
    frag->add_option("--layer", a->layer, "Layer (0 = opaque pass)");
    frag->add_option("-o,--out", a->out, "Output file (default stdout)");
    frag->add_flag("-q,--quiet", a->quiet, "Nothing on stderr but errors (fragments prints no progress)");
    return {frag, [a]() {
                checkOutFile("-o", a->out);
                checkNotInput("-o", a->out, {a->scene});
                return runFragments(*a);
            }};
}

}  // namespace pst::cli
