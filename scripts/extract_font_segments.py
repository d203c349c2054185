#!/usr/bin/env python3
"""Extract exact glyph outlines of a TrueType font as uniparam test data.

Usage (from the repository root):

    apt-get install python3-fonttools fonts-dejavu-core   # tools for this script only
    python3 scripts/extract_font_segments.py \
        [--font /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf] [--out tests/data]

(Debian's /usr/bin/python3 sees the python3-fonttools package; another
python3 first on PATH may not.)

Writes two files (docs/inputs.md):

* font_quadratics.jsonl: one line per quadratic Bezier segment of the glyphs
  of printable ASCII, Latin-1 and Latin Extended-A (U+00A1..U+017F) and the
  Greek letters (U+0391..U+03C9), in character order, then contour, then
  along the contour:
      {"glyph": "a", "contour": 0, "control": [[x0, y0], [x1, y1], [x2, y2]]}
  Straight (line) segments are left out: the file holds the quadratics only.
* glyphs.jsonl: one line per contour of the ASCII letters A-Z and a-z, as SVG
  path data with M, L (lines), Q (quadratics) and Z:
      {"glyph": "S", "contour": 0, "svg": "M 1 2 Q ... Z"}

Coordinates are exact font units. TrueType stores integers; an on-curve
point implied between two off-curve points is their midpoint, a half
integer, written "p/2" (a string) in font_quadratics.jsonl and as the exact
decimal "p.5" in the SVG paths. Glyphs whose outline is not in integer units
(scaled composite components) are skipped with a note on stderr.
"""

import argparse
import json
import sys
from fractions import Fraction

from fontTools.ttLib import TTFont


def characters():
    chars = [chr(c) for c in range(0x21, 0x7F)]
    chars += [chr(c) for c in range(0xA1, 0x180) if c != 0xAD]  # Latin-1, Latin Extended-A; no soft hyphen
    chars += [chr(c) for c in range(0x391, 0x3CA) if c != 0x3A2]  # Greek capitals and small letters
    return chars


def contours_of(glyf, name):
    """The glyph's contours as lists of (Fraction x, Fraction y, on_curve)."""
    coords, end_pts, flags = glyf[name].getCoordinates(glyf)
    contours, start = [], 0
    for end in end_pts:
        pts = []
        for k in range(start, end + 1):
            x, y = coords[k]
            if x != int(x) or y != int(y):
                raise ValueError("non-integer coordinate")
            pts.append((Fraction(int(x)), Fraction(int(y)), bool(flags[k] & 1)))
        contours.append(pts)
        start = end + 1
    return contours


def segments_of(contour):
    """The closed contour as segments: (p0, p1) lines and (p0, c, p2) quadratics."""
    n = len(contour)
    if n < 2:
        return []
    # Start at an on-curve point; with none, at the midpoint of the first two points.
    first_on = next((k for k, p in enumerate(contour) if p[2]), None)
    if first_on is None:
        a, b = contour[0], contour[1]
        start = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        seq = contour[1:] + contour[:1]
    else:
        start = contour[first_on][:2]
        seq = contour[first_on + 1:] + contour[:first_on]
    segs, cur, ctrl = [], start, None
    for x, y, on in seq + [(start[0], start[1], True)]:
        if on:
            segs.append((cur, ctrl, (x, y)) if ctrl else (cur, (x, y)))
            cur, ctrl = (x, y), None
        elif ctrl is None:
            ctrl = (x, y)
        else:
            mid = ((ctrl[0] + x) / 2, (ctrl[1] + y) / 2)
            segs.append((cur, ctrl, mid))
            cur, ctrl = mid, (x, y)
    # Drop segments of length zero (all points equal).
    return [s for s in segs if any(p != s[0] for p in s)]


def json_number(q):
    return int(q) if q.denominator == 1 else "%d/%d" % (q.numerator, q.denominator)


def svg_number(q):
    assert q.denominator in (1, 2)
    if q.denominator == 1:
        return str(q.numerator)
    return ("-" if q < 0 else "") + "%d.5" % (abs(q.numerator) // 2)


def svg_of(segs):
    out = ["M %s %s" % (svg_number(segs[0][0][0]), svg_number(segs[0][0][1]))]
    for s in segs:
        pts = s[1:]
        out.append(("Q " if len(pts) == 2 else "L ") + " ".join(svg_number(c) for p in pts for c in p))
    return " ".join(out) + " Z"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--font", default="/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")
    ap.add_argument("--out", default="tests/data")
    args = ap.parse_args()
    font = TTFont(args.font)
    cmap = font.getBestCmap()
    glyf = font["glyf"]
    quad_lines, glyph_lines = [], []
    for ch in characters():
        name = cmap.get(ord(ch))
        if name is None:
            print("no glyph for %r" % ch, file=sys.stderr)
            continue
        try:
            contours = contours_of(glyf, name)
        except ValueError as e:
            print("skipping %r: %s" % (ch, e), file=sys.stderr)
            continue
        for ci, contour in enumerate(contours):
            segs = segments_of(contour)
            for s in segs:
                if len(s) == 3:
                    quad_lines.append(json.dumps(
                        {"glyph": ch, "contour": ci,
                         "control": [[json_number(c) for c in p] for p in s]}, separators=(", ", ": ")))
            if ch.isascii() and ch.isalpha() and segs:
                glyph_lines.append(json.dumps({"glyph": ch, "contour": ci, "svg": svg_of(segs)}))
    with open(args.out + "/font_quadratics.jsonl", "w") as f:
        f.write("\n".join(quad_lines) + "\n")
    with open(args.out + "/glyphs.jsonl", "w") as f:
        f.write("\n".join(glyph_lines) + "\n")
    print("%d quadratic segments, %d letter contours" % (len(quad_lines), len(glyph_lines)), file=sys.stderr)


if __name__ == "__main__":
    main()
