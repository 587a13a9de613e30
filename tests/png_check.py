#!/usr/bin/env python3
"""png_check.py PNG CHECK ...: decodes an 8-bit RGB or RGBA PNG (the standard library only) and
checks that it is not a blank frame (more than 8 distinct colours), and each CHECK:
  R,G,B:MIN        the colour (within 40 of each channel) covers at least MIN pixels;
  R,G,B@X,Y:D      the centre of the pixels of that colour is at least D px from pixel (X, Y)
                   (a body that moved from where it started).
Prints what it found; exit 1 when a check fails, 2 when the file is not such a PNG."""
import struct
import sys
import zlib


def decode(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color = struct.unpack(">IIBB", body[:10])
            if depth != 8 or color not in (2, 6):
                raise ValueError("not 8-bit RGB(A)")
            bpp = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        if f == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif f == 2:
            line = bytearray((a + b) & 255 for a, b in zip(line, prev))
        elif f == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif f == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b, c = prev[i], prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, [tuple(r[x * bpp : x * bpp + 3]) for r in rows for x in range(width)]


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
