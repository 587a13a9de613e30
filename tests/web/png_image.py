"""PNG decoding and frame comparison for the browser checks (python3 standard library only).

decode_png handles what Chromium's screenshots and fixstep's frames are: 8-bit greyscale, RGB or
RGBA (colour types 0, 2, 6), not interlaced, any of the five filters (PNG spec, ISO/IEC
15948:2004, sections 9.2 and 11.2.2). Images are returned as (width, height, rows) with rows a
list of bytes objects of width * 3 values (RGB; alpha dropped: every fixstep frame is opaque).
"""
import struct
import zlib

_CHANNELS = {0: 1, 2: 3, 6: 4}


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def _unfilter(kind, line, prev, bpp):
    out = bytearray(line)
    n = len(out)
    if kind == 0:
        return out
    if kind == 1:
        for i in range(bpp, n):
            out[i] = (out[i] + out[i - bpp]) & 0xFF
    elif kind == 2:
        for i in range(n):
            out[i] = (out[i] + prev[i]) & 0xFF
    elif kind == 3:
        for i in range(n):
            left = out[i - bpp] if i >= bpp else 0
            out[i] = (out[i] + ((left + prev[i]) >> 1)) & 0xFF
    elif kind == 4:
        for i in range(n):
            left = out[i - bpp] if i >= bpp else 0
            upleft = prev[i - bpp] if i >= bpp else 0
            out[i] = (out[i] + _paeth(left, prev[i], upleft)) & 0xFF
    else:
        raise ValueError(f"PNG filter type {kind} is not one of 0..4")
    return out


def decode_png(path):
    """(width, height, rows of RGB bytes) of the PNG file at `path`; ValueError otherwise."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG file")
    pos, idat, header = 8, [], None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    if header is None:
        raise ValueError(f"{path}: no IHDR chunk")
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in _CHANNELS or interlace != 0:
        raise ValueError(f"{path}: bit depth {depth}, colour type {colour}, interlace {interlace}:"
                         " only 8-bit grey/RGB/RGBA, not interlaced, is read")
    channels = _CHANNELS[colour]
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        line = _unfilter(raw[start], raw[start + 1:start + 1 + stride], prev, channels)
        prev = line
        if channels == 3:
            rows.append(bytes(line))
        elif channels == 4:
            rgb = bytearray(width * 3)
            rgb[0::3], rgb[1::3], rgb[2::3] = line[0::4], line[1::4], line[2::4]
            rows.append(bytes(rgb))
        else:
            rows.append(bytes(v for g in line for v in (g, g, g)))
    return width, height, rows


def compare(a, b, threshold):
    """Compares two decoded images of the same size. Returns (mean absolute difference per
    channel value, in levels 0..255; fraction of pixels where some channel differs by more than
    `threshold` levels). ValueError when the sizes differ."""
    (wa, ha, ra), (wb, hb, rb) = a, b
    if (wa, ha) != (wb, hb):
        raise ValueError(f"sizes differ: {wa}x{ha} and {wb}x{hb}")
    total, differing = 0, 0
    for row_a, row_b in zip(ra, rb):
        diffs = [abs(x - y) for x, y in zip(row_a, row_b)]
        total += sum(diffs)
        for i in range(0, len(diffs), 3):
            if diffs[i] > threshold or diffs[i + 1] > threshold or diffs[i + 2] > threshold:
                differing += 1
    return total / (wa * ha * 3), differing / (wa * ha)


def content_fraction(image):
    """Fraction of pixels whose colour is not the image's most common one (its background): 0
    for a blank frame."""
    width, height, rows = image
    counts = {}
    for row in rows:
        for i in range(0, len(row), 3):
            key = row[i:i + 3]
            counts[key] = counts.get(key, 0) + 1
    return 1.0 - max(counts.values()) / (width * height)
