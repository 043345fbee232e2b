// Image files and image comparison through OpenImageIO (writing, reading, RMS/PSNR).
// Every write goes to a temporary file in the same folder and is renamed into place, so an
// interrupted or failed run never leaves a half-written image.
#pragma once

#include <string>

#include "render.h"

namespace pst {

enum class Tone {
    Colour,       // RGBA values in [0, 1]
    FilterWidth,  // 1 channel, entries: black at <= 1 entry, white at >= 256 (paper Fig. 9c)
};

// PNG (8-bit, values clamped) or EXR (32-bit float, values as they are), by extension.
void writeImage(const Image& img, const std::string& path, Tone tone = Tone::Colour);
Image readImage(const std::string& path);

struct ImageDiff {
    double meanError = 0, rmsError = 0, maxError = 0, psnr = 0;
    int maxX = 0, maxY = 0;   // the pixel of maxError
};
// Over the RGB channels of two RGBA images of one size (OIIO ImageBufAlgo::compare).
ImageDiff compareRgb(const Image& a, const Image& b);

// |a - b| per RGB channel times `scale` (OIIO ImageBufAlgo::absdiff), alpha 1: a difference image.
Image absDiffRgb(const Image& a, const Image& b, double scale = 1.0);

// Writes `text` to `path` atomically (temporary file, then rename).
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace pst
