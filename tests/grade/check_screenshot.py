#!/usr/bin/env python3
"""check_screenshot.py SCREENSHOT.png: does a browser's screenshot of raytracer-grade's page
show a difference picture? Counts the pixels of the difference panel's dimmed white
(grey 63: where the key is white and the images agree); a page whose picture did not
load has none. Standard library only; exit status 0 when it does, 1 when not."""
import struct, sys, zlib

def pixels(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        raise ValueError('not a PNG')
    at, idat = 8, b''
    while at < len(data):
        length, kind = struct.unpack('>I4s', data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b'IHDR':
            width, height, depth, colour = struct.unpack('>IIBB', body[:10])
            if depth != 8 or colour not in (2, 6):
                raise ValueError('not 8-bit RGB or RGBA')
            step = 3 if colour == 2 else 4
        elif kind == b'IDAT':
            idat += body
        at += 12 + length
    raw, stride, rows, previous = zlib.decompress(idat), width * step, [], bytearray(width * step)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - step] if i >= step else 0
            b, c = previous[i], previous[i - step] if i >= step else 0
            if kind == 1: line[i] = (line[i] + a) & 255
            elif kind == 2: line[i] = (line[i] + b) & 255
            elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        previous = line
    return width, height, step, rows

width, height, step, rows = pixels(sys.argv[1])
grey = sum(1 for line in rows for i in range(0, len(line), step)
           if all(60 <= line[i + k] <= 66 for k in range(3)))
print(f'screenshot {width}x{height}: {grey} pixels of the difference panel\'s dimmed white')
sys.exit(0 if grey >= 20000 else 1)
