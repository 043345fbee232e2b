#include "imageio.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace pst {
namespace fs = std::filesystem;
namespace {

OIIO::ImageBuf toBuf(const Image& img) {
    OIIO::ImageSpec spec(img.width, img.height, img.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf buf(spec);
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, img.data.data());
    return buf;
}

// Two images compared channel by channel must be of one size, with at least 3 channels (`what`
// names the caller in the refusal).
void checkRgbPair(const Image& a, const Image& b, const char* what) {
    if (a.width != b.width || a.height != b.height || a.channels < 3 || b.channels < 3)
        throw std::runtime_error(std::string(what) + ": images differ in size or have fewer than 3 channels");
}

// The RGB channels of the whole of buffer A.
OIIO::ROI rgbRoi(const OIIO::ImageBuf& A) {
    OIIO::ROI roi = A.roi();
    roi.chbegin = 0;
    roi.chend = 3;
    return roi;
}

// A temporary name in the same folder that keeps the extension (OIIO picks the format by it).
std::string tempName(const std::string& path) {
    fs::path p(path);
    return (p.parent_path() / ("." + p.stem().string() + ".tmp" + p.extension().string())).string();
}

void commit(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write (" + ec.message() + ")");
    }
}

}  // namespace

void writeImage(const Image& img, const std::string& path, Tone tone) {
    const std::string ext = fs::path(path).extension().string();
    Image out = img;
    if (tone == Tone::FilterWidth && ext != ".exr") {
        // Fig. 9c: widths from one entry (black) to 256 entries (white), on a log scale.
        for (float& v : out.data) v = float(std::clamp(std::log2(std::max(double(v), 1.0)) / 8.0, 0.0, 1.0));
    }
    OIIO::ImageBuf buf = toBuf(out);
    const std::string tmp = tempName(path);
    const bool ok = ext == ".exr" ? buf.write(tmp, OIIO::TypeDesc::FLOAT)
                                  : buf.write(tmp, OIIO::TypeDesc::UINT8);
    if (!ok) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write image: " + buf.geterror());
    }
    commit(tmp, path);
}

Image readImage(const std::string& path) {
    OIIO::ImageBuf buf(path);
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error(path + ": cannot read image: " + buf.geterror());
    const auto& spec = buf.spec();
    Image img(spec.width, spec.height, spec.nchannels);
    buf.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, img.data.data());
    return img;
}

ImageDiff compareRgb(const Image& a, const Image& b) {
    checkRgbPair(a, b, "compareRgb");
    OIIO::ImageBuf A = toBuf(a), B = toBuf(b);
    const OIIO::ROI roi = rgbRoi(A);
    auto r = OIIO::ImageBufAlgo::compare(A, B, 1e30f, 1e30f, roi);
    ImageDiff d;
    d.meanError = r.meanerror;
    d.rmsError = r.rms_error;
    d.maxError = r.maxerror;
    d.psnr = r.PSNR;
    d.maxX = r.maxx;
    d.maxY = r.maxy;
    return d;
}

Image absDiffRgb(const Image& a, const Image& b, double scale) {
    checkRgbPair(a, b, "absDiffRgb");
    OIIO::ImageBuf A = toBuf(a), B = toBuf(b);
    const OIIO::ROI roi = rgbRoi(A);
    OIIO::ImageBuf d = OIIO::ImageBufAlgo::absdiff(A, B, roi);
    if (scale != 1.0) d = OIIO::ImageBufAlgo::mul(d, float(scale));
    Image out(a.width, a.height, 4);
    std::vector<float> rgb(size_t(a.width) * a.height * 3);
    d.get_pixels(OIIO::ROI(0, a.width, 0, a.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, rgb.data());
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i) {
        for (int c = 0; c < 3; ++c) out.data[i * 4 + c] = rgb[i * 3 + c];
        out.data[i * 4 + 3] = 1.0f;
    }
    return out;
}

void writeTextFile(const std::string& path, const std::string& text) {
    const std::string tmp = tempName(path);
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out.flush()) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw std::runtime_error(path + ": cannot write");
        }
    }
    commit(tmp, path);
}

}  // namespace pst
