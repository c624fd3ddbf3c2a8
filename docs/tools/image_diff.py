#!/usr/bin/env python3
"""PSNR between two 8-bit PNG images of one size (RGB, alpha ignored) and a difference image: |a - b| per
channel, scaled by GAIN (default 8) so differences of a few levels show, written as an RGB PNG.

usage: docs/tools/image_diff.py A.png B.png DIFF.png [--gain 8]
Only the Python standard library (zlib): 8-bit RGB/RGBA, non-interlaced, as s3d writes them.
"""
import math, struct, sys, zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, color, _, _, interlace = header
    if depth != 8 or color not in (2, 6) or interlace:
        sys.exit(f"{path}: only 8-bit RGB/RGBA non-interlaced PNG files are read")
    channels = 3 if color == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1: line[i] = (line[i] + a) & 255
            elif kind == 2: line[i] = (line[i] + b) & 255
            elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line[x * channels + k] for x in range(width) for k in range(3)))
        previous = line
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + row for row in rows)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    open(path, "wb").write(png + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    gain = float(sys.argv[sys.argv.index("--gain") + 1]) if "--gain" in sys.argv else 8.0
    wa, ha, a = read_png(sys.argv[1])
    wb, hb, b = read_png(sys.argv[2])
    if (wa, ha) != (wb, hb):
        sys.exit(f"sizes differ: {wa}x{ha} and {wb}x{hb}")
    squared, worst, diff = 0, 0, []
    for ra, rb in zip(a, b):
        row = bytearray()
        for va, vb in zip(ra, rb):
            d = abs(va - vb)
            squared += d * d
            worst = max(worst, d)
            row.append(min(255, int(d * gain)))
        diff.append(bytes(row))
    write_png(sys.argv[3], wa, ha, diff)
    mse = squared / (wa * ha * 3)
    psnr = float("inf") if mse == 0 else 10 * math.log10(255 * 255 / mse)
    print(f"PSNR {psnr:.2f} dB, largest difference {worst} levels, {wa}x{ha}; difference x{gain:g} in {sys.argv[3]}")


if __name__ == "__main__":
    main()
