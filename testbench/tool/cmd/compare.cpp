// pst compare A B: mean, RMS, max and PSNR over RGB between two images (OpenImageIO's
// ImageBufAlgo::compare), like idiff: thresholds that fail the run (exit 1), a difference image
// (ImageBufAlgo::absdiff) and a JSON record.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "common.h"
#include "imageio.h"
#include "provenance.h"

namespace pst::cli {
namespace {

struct CompareArgs {
    std::string a, b, diffOut, json;
    double failPsnr = 0, failMax = 0, diffScale = 1;
    bool quiet = false;
};

// An image for compare: readable, and every pixel finite (NaN would make RMS and PSNR
// meaningless: an image full of NaN compared with itself gave RMS 0).
Image readFiniteImage(const std::string& path) {
    Image img;
    try {
        img = readImage(path);
    } catch (const std::runtime_error& e) {
        throw InputError(e.what());
    }
    for (size_t i = 0; i < img.data.size(); ++i)
        if (!std::isfinite(img.data[i])) {
            const size_t px = i / size_t(img.channels);
            throw InputError(path + ": pixel (" + std::to_string(px % size_t(img.width)) + ", " +
                             std::to_string(px / size_t(img.width)) + "): NaN or infinite value");
        }
    return img;
}

// A number as a message prints it: short (%g), not std::to_string's six decimals.
std::string shortNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

int runCompare(const CompareArgs& c, bool psnrGate, bool maxGate) {
    const Image A = readFiniteImage(c.a), B = readFiniteImage(c.b);
    if (A.width != B.width || A.height != B.height || A.channels < 3 || B.channels < 3)
        throw InputError(c.b + ": " + std::to_string(B.width) + " x " + std::to_string(B.height) + " x " +
                         std::to_string(B.channels) + " does not match " + c.a + " (" + std::to_string(A.width) + " x " +
                         std::to_string(A.height) + " x " + std::to_string(A.channels) + "; RGB needed)");
    const ImageDiff d = compareRgb(A, B);
    std::cout << "mean " << d.meanError << "  rms " << d.rmsError << "  max " << d.maxError
              << "  psnr " << d.psnr << " dB\n";
    std::vector<std::string> failed;
    // Identical images have an infinite PSNR: never below a threshold.
    if (psnrGate && d.psnr < c.failPsnr)
        failed.push_back("psnr " + shortNumber(d.psnr) + " dB is below --fail-psnr " + shortNumber(c.failPsnr));
    if (maxGate && d.maxError > c.failMax)
        failed.push_back("max " + shortNumber(d.maxError) + " at pixel (" + std::to_string(d.maxX) + ", " +
                         std::to_string(d.maxY) + ") is above --fail-max " + shortNumber(c.failMax));
    Outputs outputs;   // the difference image and the JSON record, or neither
    if (!c.diffOut.empty()) writeImage(absDiffRgb(A, B, c.diffScale), outputs.file("--diff-out", c.diffOut));
    if (!c.json.empty()) {
        nlohmann::json j = {{"a", c.a}, {"b", c.b}, {"width", A.width}, {"height", A.height},
                            {"mean", d.meanError}, {"rms", d.rmsError}, {"max", d.maxError},
                            {"max_pixel", {d.maxX, d.maxY}},
                            {"psnr", std::isfinite(d.psnr) ? nlohmann::json(d.psnr) : nlohmann::json("inf")},
                            {"fail_psnr", psnrGate ? nlohmann::json(c.failPsnr) : nlohmann::json(nullptr)},
                            {"fail_max", maxGate ? nlohmann::json(c.failMax) : nlohmann::json(nullptr)},
                            {"passed", failed.empty()}, {"failures", failed}};
        writeTextFile(outputs.file("--json", c.json), withProvenance(j).dump(2) + "\n");
    }
    outputs.commit();
    if (!c.diffOut.empty() && !c.quiet) std::cerr << "difference image: " << c.diffOut << "\n";
    for (const auto& f : failed) std::cout << "FAILED: " << f << "\n";
    return failed.empty() ? 0 : 1;
}

}  // namespace

Command registerCompare(CLI::App& app) {
    auto c = std::make_shared<CompareArgs>();
    auto* cmp = app.add_subcommand("compare", "Mean, RMS, max and PSNR between two images (RGB); exit 1 beyond a threshold");
    cmp->add_option("a", c->a, "First image")->required()->check(CLI::ExistingFile);
    cmp->add_option("b", c->b, "Second image (same size)")->required()->check(CLI::ExistingFile);
    auto* fp = cmp->add_option("--fail-psnr", c->failPsnr, "Exit 1 when the PSNR is below DB (off unless given)")
                   ->check(kFinite);
    auto* fm = cmp->add_option("--fail-max", c->failMax, "Exit 1 when a channel differs by more than X (0..1 units; "
                               "off unless given)")->check(kFinite & CLI::Range(0.0, 1e30));
    cmp->add_option("--diff-out", c->diffOut, "Write |A - B| (RGB, times --diff-scale) as an image (PNG or EXR)");
    cmp->add_option("--diff-scale", c->diffScale, "Scale of the difference image")->check(kFinite & CLI::Range(0.0, 1e6));
    cmp->add_option("--json", c->json, "Write the figures, thresholds and verdict as JSON");
    cmp->add_flag("-q,--quiet", c->quiet, "Nothing on stderr but errors");
    return {cmp, [c, fp, fm]() {
                checkOutFile("--diff-out", c->diffOut);
                if (!c->diffOut.empty() && !c->json.empty()) checkNotInput("--json", c->json, {c->diffOut});
                checkOutFile("--json", c->json);
                checkNotInput("--diff-out", c->diffOut, {c->a, c->b});
                checkNotInput("--json", c->json, {c->a, c->b});
                return runCompare(*c, fp->count() > 0, fm->count() > 0);
            }};
}

}  // namespace pst::cli
