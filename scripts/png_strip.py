#!/usr/bin/env python3
"""Join PNG pictures of one size into a strip (or a grid): python3 scripts/png_strip.py OUT.png IN1.png IN2.png ...
[--columns N] [--gap PIXELS]. The pictures are separated by white gaps (default 4 pixels) so that each frame, with
the time label `buoyancy run --png` stamps into its corner, reads on its own. Standard library only (zlib): reads
the 8-bit RGB/RGBA, non-interlaced PNGs stb_image_write makes (`buoyancy run --png`), writes 8-bit RGB. Used by
scripts/pictures.sh."""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"png_strip: {path}: not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        sys.exit(f"png_strip: {path}: only 8-bit RGB/RGBA non-interlaced PNGs are supported")
    ch = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), width * ch
    prev, rows, k = bytearray(stride), [], 0
    for _ in range(height):  # undo the PNG row filters (PNG spec section 9)
        f, line = raw[k], bytearray(raw[k + 1:k + 1 + stride])
        k += 1 + stride
        for x in range(stride):
            a = line[x - ch] if x >= ch else 0
            b = prev[x]
            c = prev[x - ch] if x >= ch else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if ch == 3 else bytes(v for i, v in enumerate(line) if i % 4 != 3))
        prev = line
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main(argv):
    columns, gap = None, 4
    if "--columns" in argv:
        i = argv.index("--columns")
        columns = int(argv[i + 1])
        del argv[i:i + 2]
    if "--gap" in argv:
        i = argv.index("--gap")
        gap = int(argv[i + 1])
        del argv[i:i + 2]
    if len(argv) < 3:
        sys.exit(__doc__)
    out, pictures = argv[1], [read_png(p) for p in argv[2:]]
    w, h = pictures[0][0], pictures[0][1]
    if any(p[0] != w or p[1] != h for p in pictures):
        sys.exit("png_strip: the pictures differ in size")
    columns = columns or len(pictures)
    lines = (len(pictures) + columns - 1) // columns
    blank, white = bytes(3 * w), b"\xff" * (3 * gap)
    width = columns * w + (columns - 1) * gap
    rows = []
    for r in range(lines):
        if r > 0:
            rows.extend([b"\xff" * (3 * width)] * gap)
        group = pictures[r * columns:(r + 1) * columns]
        group_rows = [p[2] for p in group] + [[blank] * h] * (columns - len(group))
        for y in range(h):
            rows.append(white.join(g[y] for g in group_rows))
    write_png(out, width, lines * h + (lines - 1) * gap, rows)


if __name__ == "__main__":
    main(sys.argv)
