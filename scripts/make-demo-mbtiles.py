#!/usr/bin/env python3
"""Writes an MBTiles file of made-up terrain (fields, a river, two roads) for
trying the plan view offline and for its screenshots, with nothing but the
Python standard library: no network, no map data licence.

    scripts/make-demo-mbtiles.py OUT.mbtiles [--lat 52.21 --lon 0.14 --radius-km 6 --zoom 11-15]

Real offline maps come from tools that cut MBTiles from OpenStreetMap or
aerial imagery (e.g. MOBAC, QGIS, tilemaker); the console reads those the same way.
"""
import argparse
import math
import sqlite3
import struct
import zlib


def png(width, height, rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def tile_of(lat, lon, z):
    n = 2 ** z
    x = (lon + 180) / 360 * n
    y = (1 - math.asinh(math.tan(math.radians(lat))) / math.pi) / 2 * n
    return x, y


def geo_of(px, py, z):
    n = 256 * 2 ** z
    lon = px / n * 360 - 180
    lat = math.degrees(math.atan(math.sinh(math.pi * (1 - 2 * py / n))))
    return lat, lon


FIELDS = [(196, 214, 160), (182, 206, 146), (214, 222, 170), (170, 196, 140), (222, 214, 176)]


def colour(lat, lon, metres_per_pixel):
    # A river winding west to east, and two straight roads; widths in metres.
    river = 52.2065 + 0.0035 * math.sin(lon * 160) + 0.0012 * math.sin(lon * 530)
    d_river = abs(lat - river) * 111_000
    if d_river < max(18, 1.5 * metres_per_pixel):
        return (120, 168, 214)
    road1 = (lat - 52.19) - 0.35 * (lon - 0.10)
    road2 = lon - 0.152 - 0.1 * (lat - 52.2)
    if abs(road1) * 111_000 < max(6, metres_per_pixel) or abs(road2) * 68_000 < max(6, metres_per_pixel):
        return (250, 250, 246)
    # Fields: cells of about 300 m, each one of a few crops.
    i = int(math.floor(lat * 370)) * 7919 + int(math.floor(lon * 240)) * 104729
    base = FIELDS[(i ^ (i >> 7)) % len(FIELDS)]
    wood = math.sin(lat * 900) * math.sin(lon * 700) > 0.82
    return (120, 160, 110) if wood else base


def tile_png(z, x, y):
    rows = []
    mpp = 156543.034 * math.cos(math.radians(geo_of(x * 256 + 128, y * 256 + 128, z)[0])) / 2 ** z
    for py in range(256):
        row = bytearray()
        for px in range(256):
            lat, lon = geo_of(x * 256 + px + 0.5, y * 256 + py + 0.5, z)
            row += bytes(colour(lat, lon, mpp))
        rows.append(row)
    return png(256, 256, rows)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("--lat", type=float, default=52.212)
    p.add_argument("--lon", type=float, default=0.142)
    p.add_argument("--radius-km", type=float, default=5)
    p.add_argument("--zoom", default="11-14")
    a = p.parse_args()
    lo, hi = (int(v) for v in a.zoom.split("-"))
    dlat = a.radius_km / 111.0
    dlon = a.radius_km / (111.0 * math.cos(math.radians(a.lat)))
    db = sqlite3.connect(a.out)
    db.executescript("DROP TABLE IF EXISTS metadata; DROP TABLE IF EXISTS tiles;"
                     "CREATE TABLE metadata (name TEXT, value TEXT);"
                     "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, tile_data BLOB);"
                     "CREATE UNIQUE INDEX tile_index ON tiles (zoom_level, tile_column, tile_row);")
    meta = {"name": "Demo terrain", "format": "png", "type": "baselayer", "version": "1",
            "attribution": "Made-up terrain (scripts/make-demo-mbtiles.py)",
            "bounds": f"{a.lon - dlon},{a.lat - dlat},{a.lon + dlon},{a.lat + dlat}",
            "minzoom": str(lo), "maxzoom": str(hi)}
    db.executemany("INSERT INTO metadata VALUES (?, ?)", meta.items())
    count = 0
    for z in range(lo, hi + 1):
        x0, y0 = tile_of(a.lat + dlat, a.lon - dlon, z)
        x1, y1 = tile_of(a.lat - dlat, a.lon + dlon, z)
        for x in range(int(x0), int(x1) + 1):
            for y in range(int(y0), int(y1) + 1):
                tms = 2 ** z - 1 - y  # MBTiles rows count from the south
                db.execute("INSERT INTO tiles VALUES (?, ?, ?, ?)", (z, x, tms, tile_png(z, x, y)))
                count += 1
    db.commit()
    print(f"{a.out}: {count} tiles, zoom {lo}-{hi}")


if __name__ == "__main__":
    main()
