"""Text on the pictures, drawn with Pillow onto the figure's Agg raster.

matplotlib lays out and rasterizes every text of every figure anew (its glyph and layout
caches live with one figure's renderer): on this project's machine 0.1-0.4 ms per glyph
and a few ms per text, so a force-space plot's few hundred glyphs cost more than all of
its drawing.  The pictures therefore draw lines, markers and polygons with matplotlib
(object API, Agg canvas) and write their text as ``Label`` values, which ``Picture.png``
renders with Pillow's FreeType in the same font (matplotlib's DejaVu Sans) after the
canvas is drawn, at positions taken from the figure's own transforms.  Pillow's basic
layout engine is used (no text shaping library): the same text gives the same pixels.
"""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from furncheck.export.errors import ExportUnavailable

PNG_ZLIB_LEVEL = 1
"""zlib level of the PNG files: 1, zlib's fastest; the pictures' large flat areas keep
them at 20-110 kB."""
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
HALO_WIDTH = 2
"""Pixels of a haloed label's white outline."""
LINE_SPACING = 1.2
"""Distance between the baselines of a label's lines, in font heights (ascent + descent)."""


@dataclass(frozen=True)
class Label:
    """A text at figure pixel (x, y), origin at the bottom left as in matplotlib's display
    coordinates; ``size`` in points; ``colour`` RGB 0..1; ``ha`` left|center|right and
    ``va`` top|center|bottom place the text's box (all its lines) at the point;
    ``rotation`` 0 or 90 (degrees counter-clockwise: a y-axis label)."""

    x: float
    y: float
    text: str
    size: float = 8.0
    colour: tuple[float, float, float] = (0.0, 0.0, 0.0)
    ha: str = "left"
    va: str = "bottom"
    bold: bool = False
    rotation: int = 0
    halo: bool = False       # a white outline, for text over the drawing


@dataclass
class Picture:
    """A figure (Agg canvas) and the labels to write on it."""

    figure: object
    labels: list[Label] = field(default_factory=list)

    @property
    def texts(self) -> list[str]:
        """Every label's text, in drawing order."""
        return [label.text for label in self.labels]

    def image(self):
        """The figure drawn, labels written: a Pillow RGB image."""
        canvas = self.figure.canvas
        canvas.draw()
        pixels = np.asarray(canvas.buffer_rgba())[..., :3]
        image = _pil().Image.fromarray(np.ascontiguousarray(pixels), "RGB")
        draw_labels(image, self.labels, self.figure.dpi)
        return image

    def png(self) -> bytes:
        """PNG bytes of ``image`` (``png_bytes``)."""
        return png_bytes(np.asarray(self.image()))


def png_bytes(rgb: np.ndarray) -> bytes:
    """A PNG file of an (h, w, 3) uint8 image: 8-bit RGB, no row filters, one zlib
    stream at PNG_ZLIB_LEVEL, no text chunks (no software version), so the same pixels
    give the same bytes.  Written here: Pillow's encoder, which tries a filter per row,
    takes twice as long for these pictures and writes larger files."""
    height, width = rgb.shape[:2]
    rows = np.empty((height, 1 + 3 * width), dtype=np.uint8)
    rows[:, 0] = 0                                   # filter type 0 (none) on every row
    rows[:, 1:] = rgb[..., :3].reshape(height, -1)
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)   # 8-bit RGB
    return b"".join([PNG_MAGIC, _chunk(b"IHDR", header),
                     _chunk(b"IDAT", zlib.compress(rows.tobytes(), PNG_ZLIB_LEVEL)),
                     _chunk(b"IEND", b"")])


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


class Sheet:
    """Where a panel draws: the figure, and the transform from the panel's own
    coordinates to figure pixels.  Artists go straight onto the figure, not into a
    matplotlib Axes (creating an Axes costs more than drawing a whole panel); ``gid``
    tags them with the panel's name."""

    def __init__(self, figure, transform, gid: str | None = None):
        self.figure = figure
        self.transform = transform
        self.gid = gid

    def add(self, artist):
        artist.set_transform(self.transform)
        artist.set_clip_on(False)
        if self.gid:
            artist.set_gid(self.gid)
        self.figure.add_artist(artist)
        return artist

    def pixels(self, points) -> np.ndarray:
        """(n, 2) figure pixels of points in the panel's coordinates."""
        return self.transform.transform(np.asarray(points, dtype=float).reshape(-1, 2))

    def points(self, pixels) -> np.ndarray:
        """(n, 2) panel coordinates of figure pixels."""
        return self.transform.inverted().transform(
            np.asarray(pixels, dtype=float).reshape(-1, 2))


def draw_labels(image, labels: list[Label], dpi: float) -> None:
    """Write ``labels`` onto the Pillow image (figure pixels, origin bottom left)."""
    pil = _pil()
    draw = pil.ImageDraw.Draw(image)
    height = image.height
    for label in labels:
        font = _font(label.bold, max(1, round(label.size * dpi / 72.0)))
        fill = tuple(int(round(255 * c)) for c in label.colour)
        if label.rotation == 90:
            _draw_rotated(image, label, font, fill)
            continue
        _draw_block(draw, label.text.split("\n"), font, fill, label.x, height - label.y,
                    label.ha, label.va, HALO_WIDTH if label.halo else 0)


def _draw_block(draw, lines: list[str], font, fill, x: float, y: float, ha: str,
                va: str, halo: int = 0) -> None:
    """Lines of text with their block's ``ha``/``va`` at Pillow pixel (x, y) (y down)."""
    ascent, descent = font.getmetrics()
    step = LINE_SPACING * (ascent + descent)
    block = ascent + descent + step * (len(lines) - 1)
    top = y if va == "top" else y - block if va == "bottom" else y - block / 2
    anchor = {"left": "ls", "center": "ms", "right": "rs"}[ha]
    for k, line in enumerate(lines):
        draw.text((x, top + ascent + k * step), line, font=font, fill=fill, anchor=anchor,
                  stroke_width=halo, stroke_fill=(255, 255, 255))


def _draw_rotated(image, label: Label, font, fill) -> None:
    """A label turned 90 degrees counter-clockwise, centred on its point."""
    pil = _pil()
    ascent, descent = font.getmetrics()
    width = int(np.ceil(font.getlength(label.text))) + 2
    tile = pil.Image.new("L", (width, ascent + descent + 2), 0)
    pil.ImageDraw.Draw(tile).text((1, 1 + ascent), label.text, font=font, fill=255,
                                  anchor="ls")
    tile = tile.rotate(90, expand=True)
    colour = pil.Image.new("RGB", tile.size, fill)
    left = int(round(label.x - tile.width / 2))
    top = int(round(image.height - label.y - tile.height / 2))
    image.paste(colour, (left, top), tile)


@lru_cache(maxsize=32)
def _font(bold: bool, pixels: int):
    import matplotlib

    pil = _pil()
    name = "DejaVuSans-Bold.ttf" if bold else "DejaVuSans.ttf"
    path = f"{matplotlib.get_data_path()}/fonts/ttf/{name}"
    return pil.ImageFont.truetype(path, pixels, layout_engine=pil.ImageFont.Layout.BASIC)


def _pil():
    """The Pillow modules (installed with matplotlib)."""
    try:
        import PIL.Image
        import PIL.ImageDraw
        import PIL.ImageFont
    except ImportError as error:
        raise ExportUnavailable("matplotlib") from error
    return PIL


def to_rgb(colour) -> tuple[float, float, float]:
    """An RGB triple from a matplotlib colour ('0.25', 'tab:red', (r, g, b))."""
    from matplotlib.colors import to_rgb as convert

    return tuple(float(c) for c in convert(colour))
