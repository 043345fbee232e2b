// The scene's time track ([animation] frames, fps, [[animation.track]] field + keys): parsed,
// and applied to a scene's TOML tree at time t before the scene is built (scene.cpp).
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "scene_parse.h"

namespace pst::scene_detail {
namespace {

// --- Time track: [animation] frames, fps, [[animation.track]] field + keys -----------------
struct Seg {
    std::string key;
    int index = -1;    // key[N]
    bool all = false;  // key[*]
};

bool parseFieldPath(const std::string& s, std::vector<Seg>* out) {
    std::stringstream ss(s);
    std::string part;
    while (std::getline(ss, part, '.')) {
        Seg g;
        size_t b = part.find('[');
        g.key = part.substr(0, b);
        if (g.key.empty()) return false;
        if (b != std::string::npos) {
            if (part.back() != ']') return false;
            std::string ix = part.substr(b + 1, part.size() - b - 2);
            if (ix == "*") g.all = true;
            else {
                if (ix.empty() || ix.size() > 4 || ix.find_first_not_of("0123456789") != std::string::npos) return false;
                g.index = std::stoi(ix);
            }
        }
        out->push_back(g);
    }
    return !out->empty() && !s.empty() && s.back() != '.';
}

// The tables that hold the path's last key (several with [*]); "" or what does not resolve.
std::vector<toml::table*> leafTables(toml::table& root, const std::vector<Seg>& segs, std::string* err) {
    std::vector<toml::table*> cur{&root};
    for (size_t i = 0; i + 1 < segs.size(); ++i) {
        const Seg& g = segs[i];
        std::vector<toml::table*> next;
        for (toml::table* t : cur) {
            toml::node* n = t->get(g.key);
            if (!n) { *err = "'" + g.key + "' is not in the file"; return {}; }
            if (g.all || g.index >= 0) {
                toml::array* a = n->as_array();
                if (!a) { *err = "'" + g.key + "' is not an array"; return {}; }
                if (g.index >= int(a->size())) {
                    *err = "'" + g.key + "' has " + std::to_string(a->size()) + " entries";
                    return {};
                }
                for (size_t k = 0; k < a->size(); ++k) {
                    if (g.index >= 0 && int(k) != g.index) continue;
                    toml::table* e = a->get(k)->as_table();
                    if (!e) { *err = "'" + g.key + "' entries are not tables"; return {}; }
                    next.push_back(e);
                }
            } else {
                toml::table* e = n->as_table();
                if (!e) { *err = "'" + g.key + "' is not a table (index it: " + g.key + "[N] or [*])"; return {}; }
                next.push_back(e);
            }
        }
        cur = std::move(next);
    }
    if (segs.back().all || segs.back().index >= 0) {
        *err = "the last part names a field, not an array entry";
        return {};
    }
    return cur;
}

std::vector<Seg> trackPath(const Track& tr) {
    std::vector<Seg> segs;
    parseFieldPath(tr.field, &segs);
    return segs;
}

}  // namespace

void applyTrack(toml::table& root, const Track& tr, double t) {
    std::string err;
    const std::vector<Seg> segs = trackPath(tr);
    const std::vector<double> v = tr.at(t);
    for (toml::table* tb : leafTables(root, segs, &err)) {
        if (v.size() == 1) tb->insert_or_assign(segs.back().key, v[0]);
        else {
            toml::array a;
            for (double x : v) a.push_back(x);
            tb->insert_or_assign(segs.back().key, std::move(a));
        }
    }
}

Animation parseAnimation(const Ctx& c, toml::table& root) {
    Animation an;
    const toml::node* node = find(root, "animation");
    if (!node) return an;
    const toml::table* at = node->as_table();
    if (!at) c.fail(node, "animation", "expected a table");
    checkKeys(c, *at, "animation", {"frames", "fps", "track"});
    an.frames = getInt(c, *at, "animation", "frames", 0, 1, 10000);
    an.fps = getNumber(c, *at, "animation", "fps", an.fps);
    if (an.fps <= 0 || an.fps > 240) c.fail(find(*at, "fps"), "animation.fps", "must be in (0, 240]");
    const toml::node* tn = find(*at, "track");
    if (!tn) c.fail(at, "animation.track", "missing: one or more [[animation.track]] tables");
    const toml::array* ta = tn->as_array();
    if (!ta || !ta->is_array_of_tables() || ta->empty())
        c.fail(tn, "animation.track", "expected one or more [[animation.track]] tables");
    if (ta->size() > 256) c.fail(tn, "animation.track", "at most 256 tracks");
    for (size_t i = 0; i < ta->size(); ++i) {
        const std::string tp = "animation.track[" + std::to_string(i) + "]";
        const toml::table& tt = *ta->get(i)->as_table();
        checkKeys(c, tt, tp, {"field", "keys"});
        Track tr;
        tr.where = inputWhere(c.file, lineOf(&tt));
        const toml::node* fn = find(tt, "field");
        if (!fn) c.fail(&tt, join(tp, "field"), "missing");
        tr.field = getString(c, tt, tp, "field", "");
        std::vector<Seg> segs;
        if (!parseFieldPath(tr.field, &segs))
            c.fail(fn, join(tp, "field"), "'" + tr.field + "' is not a field path (e.g. camera.eye, "
                                           "textures.NAME.octaves[*].offset, objects[0].tex_rotate)");
        if (segs[0].key != "camera" && segs[0].key != "textures" && segs[0].key != "objects")
            c.fail(fn, join(tp, "field"), "'" + tr.field + "': only camera, textures and objects fields can be animated");
        std::string err;
        std::vector<toml::table*> leaves = leafTables(root, segs, &err);
        if (!err.empty()) c.fail(fn, join(tp, "field"), "'" + tr.field + "': " + err);
        // An existing field fixes the number of values; a missing one (e.g. tex_rotate) is
        // checked by the scene parser at every key below.
        size_t want = 0;
        for (toml::table* tb : leaves)
            if (const toml::node* leaf = tb->get(segs.back().key)) {
                if (leaf->is_number()) want = 1;
                else if (leaf->is_array()) want = leaf->as_array()->size();
                else c.fail(fn, join(tp, "field"), "'" + tr.field + "' is not a number or an array of numbers");
            }
        const toml::node* kn = find(tt, "keys");
        if (!kn) c.fail(&tt, join(tp, "keys"), "missing");
        const toml::array* ka = kn->as_array();
        if (!ka || ka->empty()) c.fail(kn, join(tp, "keys"), "expected an array of [t, value...] keys");
        if (ka->size() > 4096) c.fail(kn, join(tp, "keys"), "at most 4096 keys");
        for (size_t k = 0; k < ka->size(); ++k) {
            const std::string kp = join(tp, "keys") + "[" + std::to_string(k) + "]";
            std::vector<double> v = asNumbers(c, *ka->get(k), kp, 2, 5);
            TrackKey key{v[0], std::vector<double>(v.begin() + 1, v.end())};
            if (key.t < 0 || key.t > 1) c.fail(ka->get(k), kp, "time must be in [0, 1] (the whole sequence)");
            if (!tr.keys.empty() && key.t < tr.keys.back().t) c.fail(ka->get(k), kp, "times must not decrease");
            if (want && key.value.size() != want)
                c.fail(ka->get(k), kp, "'" + tr.field + "' takes " + std::to_string(want) + " number(s), got " +
                                           std::to_string(key.value.size()));
            if (!tr.keys.empty() && key.value.size() != tr.keys[0].value.size())
                c.fail(ka->get(k), kp, "every key must have as many values as the first");
            tr.keys.push_back(std::move(key));
        }
        an.tracks.push_back(std::move(tr));
    }
    return an;
}

}  // namespace pst::scene_detail
