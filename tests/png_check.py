#!/usr/bin/env python3
"""png_check.py PNG CHECK ...: decodes an 8-bit RGB or RGBA PNG (the standard library only) and
checks that it is not a blank frame (more than 8 distinct colours), and each CHECK:
  R,G,B:MIN        the colour (within 40 of each channel) covers at least MIN pixels;
  R,G,B@X,Y:D      the centre of the pixels of that colour is at least D px from pixel (X, Y)
                   (a body that moved from where it started).
Prints what it found; exit 1 when a check fails, 2 when the file is not such a PNG."""
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "web"))
from png_image import decode_png  # noqa: E402  (the browser checks' decoder)


def decode(path):
    """(width, pixels as RGB tuples in row order) of the PNG at `path`."""
    width, _, rows = decode_png(path)
    return width, [tuple(r[x * 3 : x * 3 + 3]) for r in rows for x in range(width)]


def near(p, want):
    return all(abs(a - b) <= 40 for a, b in zip(p, want))


def main():
    try:
        width, pixels = decode(sys.argv[1])
    except (OSError, ValueError, zlib.error, struct.error) as e:
        print(f"{sys.argv[1]}: {e}")
        return 2
    counts = {}
    for p in pixels:
        counts[p] = counts.get(p, 0) + 1
    ok = len(counts) > 8
    print(f"{sys.argv[1]}: {len(counts)} colours")
    for spec in sys.argv[2:]:
        if "@" in spec:
            rgb, rest = spec.split("@")
            xy, least = rest.split(":")
            want = tuple(int(v) for v in rgb.split(","))
            x0, y0 = (float(v) for v in xy.split(","))
            found = [(i % width, i // width) for i, p in enumerate(pixels) if near(p, want)]
            if not found:
                print(f"  {rgb}: no pixel")
                ok = False
                continue
            cx = sum(x for x, _ in found) / len(found)
            cy = sum(y for _, y in found) / len(found)
            d = ((cx - x0) ** 2 + (cy - y0) ** 2) ** 0.5
            print(f"  {rgb}: centre ({cx:.0f}, {cy:.0f}), {d:.0f} px from ({x0:.0f}, {y0:.0f}) (at least {least})")
            ok = ok and d >= float(least)
            continue
        rgb, least = spec.split(":")
        want = tuple(int(v) for v in rgb.split(","))
        n = sum(c for p, c in counts.items() if near(p, want))
        print(f"  {rgb}: {n} pixels (at least {least})")
        ok = ok and n >= int(least)
    return 0 if ok else 1


sys.exit(main())
