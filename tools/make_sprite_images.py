#!/usr/bin/env python3
"""Writes the images of assets/scenes/sprites.toml into assets/scenes/sprites/ (committed), with
zlib and struct only: crate.png (16x16, opaque: planks, a dark frame and a light top-left corner
so that its turn shows), ball.png (16x16: a striped disc, transparent outside it) and tiles.png
(8x8: a two-tone checker with a dot in its top-left tile)."""
import os
import struct
import zlib


def png(path, w, h, pixel):
    """pixel(x, y) -> (r, g, b, a), y = 0 the top row."""
    raw = b"".join(b"\x00" + b"".join(bytes(pixel(x, y)) for x in range(w)) for y in range(h))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def crate(x, y):
    if x < 4 and y < 4:
        return (250, 240, 200, 255)  # the top-left corner
    if x in (0, 15) or y in (0, 15):
        return (70, 40, 20, 255)
    if x == y or x == 15 - y:
        return (110, 70, 35, 255)  # the cross brace
    return (190, 130, 70, 255) if (y // 3) % 2 == 0 else (170, 112, 58, 255)


def ball(x, y):
    dx, dy = x - 7.5, y - 7.5
    if dx * dx + dy * dy > 7.5 * 7.5:
        return (0, 0, 0, 0)
    if abs(dy) < 2.0:
        return (250, 250, 250, 255)  # a stripe across: the roll shows
    return (40, 120, 220, 255) if dx < 0 else (220, 60, 60, 255)


def tiles(x, y):
    if 1 <= x <= 2 and 1 <= y <= 2:
        return (60, 70, 95, 255)
    return (34, 40, 56, 255) if (x // 4 + y // 4) % 2 == 0 else (28, 33, 46, 255)


out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenes", "sprites")
png(os.path.join(out, "crate.png"), 16, 16, crate)
png(os.path.join(out, "ball.png"), 16, 16, ball)
png(os.path.join(out, "tiles.png"), 8, 8, tiles)
