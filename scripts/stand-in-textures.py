#!/usr/bin/env python3
"""Writes stand-in albedo maps for the textures a model's .mtl names but its folder lacks.

The shared Sibenik model names kamen.png, KAMEN-stup.png and mramor6x6.png, which its licence-clean copy does
not carry. Measuring what drawing albedo maps costs needs maps of a realistic size and content, not the real
ones: each stand-in is a 512 x 512 sRGB PNG of stone blocks (mortar lines, per-block tone, fine noise) in a
tone taken from a hash of its name. Usage: stand-in-textures.py MODEL.mtl OUT_FOLDER (then set
[model] textures = ["OUT_FOLDER"] in the scene).
"""
import hashlib
import random
import struct
import sys
import zlib
from pathlib import Path

SIDE = 512
BLOCKS = 4  # blocks per side


def png(path: Path, rows: list) -> None:
    raw = b"".join(b"\x00" + bytes(r) for r in rows)

    def chunk(tag: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", SIDE, SIDE, 8, 2, 0, 0, 0)  # 8-bit RGB
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 6))
                     + chunk(b"IEND", b""))


def stone(name: str) -> list:
    digest = hashlib.sha256(name.encode()).digest()
    base = [120 + digest[i] % 100 for i in range(3)]
    rng = random.Random(digest)
    tone = [[rng.uniform(0.8, 1.2) for _ in range(BLOCKS)] for _ in range(BLOCKS)]
    cell = SIDE // BLOCKS
    rows = []
    for y in range(SIDE):
        row = []
        shift = (cell // 2) if (y // cell) % 2 else 0  # running bond
        for x in range(SIDE):
            bx, by = ((x + shift) % SIDE) // cell, y // cell
            mortar = (x + shift) % cell < 6 or y % cell < 6
            k = 0.45 if mortar else tone[by][bx] * rng.uniform(0.92, 1.08)
            row.extend(max(0, min(255, int(c * k))) for c in base)
        rows.append(row)
    return rows


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    mtl, out = Path(sys.argv[1]), Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    names = sorted({line.split(None, 1)[1].strip() for line in mtl.read_text(errors="replace").splitlines()
                    if line.strip().startswith("map_Kd")})
    for name in names:
        png(out / Path(name.replace("\\", "/")).name, stone(name))
        print(f"{out / Path(name).name}: stand-in for {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
