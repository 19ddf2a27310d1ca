#!/usr/bin/env python3
"""Compares two PNGs written by `penumbra render` (8- or 16-bit, gray or RGB(A), no
interlace) sample by sample, with the standard library only (the device machine has no
imaging packages): prints how many samples differ, by how much at most, and the share of
pixels that differ. Exit status 0 when the images have the same size.

Usage: png_diff.py A.png B.png
"""
import struct
import sys
import zlib

CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}


def unfilter(rows, stride, bpp):
    out = []
    previous = bytearray(stride)
    for filter_type, row in rows:
        current = bytearray(row)
        for i in range(stride):
            left = current[i - bpp] if i >= bpp else 0
            up = previous[i]
            corner = previous[i - bpp] if i >= bpp else 0
            if filter_type == 1:
                current[i] = (current[i] + left) & 0xFF
            elif filter_type == 2:
                current[i] = (current[i] + up) & 0xFF
            elif filter_type == 3:
                current[i] = (current[i] + (left + up) // 2) & 0xFF
            elif filter_type == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else corner)
                current[i] = (current[i] + predictor) & 0xFF
        out.append(bytes(current))
        previous = current
    return out


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    offset, idat, header = 8, b"", None
    while offset < len(data):
        length, kind = struct.unpack(">I4s", data[offset:offset + 8])
        body = data[offset + 8:offset + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        offset += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if interlace or colour not in CHANNELS or depth not in (8, 16):
        raise SystemExit(f"{path}: unsupported PNG layout")
    bytes_per_sample = depth // 8
    bpp = CHANNELS[colour] * bytes_per_sample
    stride = width * bpp
    raw = zlib.decompress(idat)
    rows = [(raw[y * (stride + 1)], raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)]) for y in range(height)]
    pixels = b"".join(unfilter(rows, stride, bpp))
    if bytes_per_sample == 2:
        samples = struct.unpack(f">{len(pixels) // 2}H", pixels)
    else:
        samples = list(pixels)
    return width, height, CHANNELS[colour], samples


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    a, b = read_png(sys.argv[1]), read_png(sys.argv[2])
    if a[:3] != b[:3]:
        print(f"different sizes: {a[:3]} vs {b[:3]}")
        return 1
    channels = a[2]
    differing = [i for i, (x, y) in enumerate(zip(a[3], b[3])) if x != y]
    worst = max((abs(a[3][i] - b[3][i]) for i in differing), default=0)
    pixels = len({i // channels for i in differing})
    total = a[0] * a[1]
    print(f"{len(differing)} samples differ (max {worst}); {pixels} of {total} pixels ({100.0 * pixels / total:.4f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
