"""Images of the figures: OpenImageIO reading and writing (atomic), resizing, boxes, a canvas
with text labels."""
import subprocess
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

from .. import atomic
from .figdata import InputMissing, progress, rel

CANVAS = (24, 24, 28)       # background of the mosaics
HEADER_FG = (1.0, 1.0, 1.0)
FONTS = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation2/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/lato/Lato-Regular.ttf",
]



def write_png(path, rgb):
    """rgb: H x W x 3 uint8."""
    h, w, c = rgb.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, oiio.UINT8))
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, c), np.ascontiguousarray(rgb))

    def write(tmp):
        if not buf.write(str(tmp)):
            raise RuntimeError(f"{path}: cannot write: {buf.geterror()}")
    atomic.write_with(path, write)


def read_rgb(path):
    buf = oiio.ImageBuf(str(path))
    px = buf.get_pixels(oiio.UINT8)
    if buf.has_error or px is None or px.ndim != 3:
        raise InputMissing(f"{rel(path)}: cannot read image: {buf.geterror()}")
    if px.shape[2] == 1:
        px = np.repeat(px, 3, axis=2)
    return np.ascontiguousarray(px[:, :, :3])


def resize(rgb, w, h):
    """Filtered resize (downscaling) to w x h."""
    if rgb.shape[1] == w and rgb.shape[0] == h:
        return rgb
    src = oiio.ImageBuf(oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, oiio.UINT8))
    src.set_pixels(src.roi, np.ascontiguousarray(rgb))
    dst = oiio.ImageBufAlgo.resize(src, roi=oiio.ROI(0, w, 0, h, 0, 1, 0, 3))
    return dst.get_pixels(oiio.UINT8)[:, :, :3]


def fit(rgb, box_w, box_h):
    """Scale to fit a box, keeping the aspect ratio."""
    h, w = rgb.shape[:2]
    k = min(box_w / w, box_h / h)
    return resize(rgb, max(1, round(w * k)), max(1, round(h * k)))


def zoom_nearest(rgb, w, h):
    """Nearest-neighbour resize to w x h (pixels stay visible as blocks)."""
    ys = np.minimum((np.arange(h) * rgb.shape[0]) // h, rgb.shape[0] - 1)
    xs = np.minimum((np.arange(w) * rgb.shape[1]) // w, rgb.shape[1] - 1)
    return rgb[ys][:, xs]


def draw_box(rgb, x0, y0, x1, y1, colour, t=2):
    """Rectangle outline [x0, x1) x [y0, y1), t pixels thick, inside the box."""
    c = np.array(colour, np.uint8)
    rgb[y0:y0 + t, x0:x1] = c
    rgb[y1 - t:y1, x0:x1] = c
    rgb[y0:y1, x0:x0 + t] = c
    rgb[y0:y1, x1 - t:x1] = c


# ---------------------------------------------------------------------------------------------
# Canvas with text labels (OpenImageIO render_text; labels dropped when no font works)


class Canvas:
    font = None            # path of a working font, or "" when none works
    font_checked = False

    def __init__(self, w, h):
        self.px = np.empty((h, w, 3), np.uint8)
        self.px[:] = CANVAS
        self.labels = []

    def paste(self, rgb, x, y):
        h, w = rgb.shape[:2]
        self.px[y:y + h, x:x + w] = rgb

    def text(self, x, y, s, size=16, colour=HEADER_FG, align="left"):
        """Baseline at y; a label whose baseline is outside the canvas is left out."""
        self.labels.append((x, y, s, size, colour, align))

    @classmethod
    def find_font(cls):
        if cls.font_checked:
            return cls.font
        cls.font_checked = True
        cls.font = ""
        probe = oiio.ImageBuf(oiio.ImageSpec(64, 32, 3, oiio.FLOAT))
        candidates = list(FONTS)
        try:
            r = subprocess.run(["fc-match", "-f", "%{file}", "sans"], capture_output=True, text=True, timeout=10)
            if r.returncode == 0 and r.stdout:
                candidates.append(r.stdout.strip())
        except (OSError, subprocess.SubprocessError):
            pass
        for f in candidates:
            if Path(f).exists() and oiio.ImageBufAlgo.render_text(probe, 2, 20, "A", 12, f, (1, 1, 1)):
                cls.font = f
                break
        if not cls.font:
            progress("no font works with OpenImageIO's render_text: images unlabelled, labels in the captions")
        return cls.font

    def finish(self):
        font = self.find_font()
        if not self.labels or not font:
            return self.px
        h, w = self.px.shape[:2]
        buf = oiio.ImageBuf(oiio.ImageSpec(w, h, 3, oiio.UINT8))
        buf.set_pixels(buf.roi, self.px)
        for x, y, s, size, colour, align in self.labels:
            if 0 < y <= h:        # OpenImageIO aborts on text wholly outside the image (small images)
                oiio.ImageBufAlgo.render_text(buf, int(x), int(y), s, int(size), font, tuple(colour), align)
        return buf.get_pixels(oiio.UINT8)[:, :, :3]

    @classmethod
    def labelled(cls):
        return bool(cls.find_font())

