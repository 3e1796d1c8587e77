#!/usr/bin/python3
"""gen_models.py: write the oracle's generated scenes into a directory (default
build/oracle/models). Small, deterministic, regenerated on every run; nothing here is committed.

  sphere.obj    watertight UV sphere (shared vertices, one vertex per pole, seam closed), vn given
  grid.obj      200x200 quads (fanned by the readers), wavy height field, NO normals (generated)
  ground.obj    100x100 ground quad at y=0, uvs 0..50 (repeat wrap), one vn
  huge.obj      1e6-sized ground triangle (crosses the near plane, runs past far) and wall
  tie.obj       64x64-unit orthographic mosaic whose vertices sit on pixel centres at
                --size 64x64 --ortho 64 (window = world + 32): every edge runs through centres
  tie.ppm       32x32 texture of distinct colours; each tie triangle samples one texel centre
  checker.ppm   64x64 coloured checker for the ground plane
  grid.stl      grid.obj's triangles (quads fanned as the readers do) as binary STL
  globe.obj/.mtl/.png  textured UV sphere (vt, vn, map_Kd) placed in the world
  globe.glb     the same sphere as glTF binary: local coordinates under a node with
                rotation, scale and translation, normals, uvs (v flipped, as glTF stores
                them), the PNG embedded: rendered by rastty, compared with Mesa's globe.obj
No object colour is ever magenta (255,0,255): the crack scenes rely on it.
"""
import json
import math
import os
import random
import struct
import sys
import zlib


def write(path, lines):
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def sphere(path, seg=96, rings=48):
    out = ["# UV sphere, radius 1, watertight"]
    out.append("v 0 1 0")  # north pole = 1
    for r in range(1, rings):
        th = math.pi * r / rings
        for s in range(seg):
            ph = 2 * math.pi * s / seg
            out.append("v %.9f %.9f %.9f" % (math.sin(th) * math.cos(ph), math.cos(th),
                                              -math.sin(th) * math.sin(ph)))
    out.append("v 0 -1 0")  # south pole
    south = 2 + (rings - 1) * seg
    # normals equal positions on a unit sphere: vn index = v index
    n = len([l for l in out if l.startswith("v ")])
    out += [l.replace("v ", "vn ", 1) for l in out if l.startswith("v ")]

    def ring(r, s):  # 1-based index of ring r (1..rings-1), segment s
        return 2 + (r - 1) * seg + (s % seg)

    for s in range(seg):  # CCW seen from outside
        out.append("f 1//1 %d//%d %d//%d" % (ring(1, s), ring(1, s), ring(1, s + 1), ring(1, s + 1)))
    for r in range(1, rings - 1):
        for s in range(seg):
            a, b, c, d = ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s + 1)
            out.append("f %d//%d %d//%d %d//%d %d//%d" % (a, a, b, b, c, c, d, d))
    for s in range(seg):
        a, b = ring(rings - 1, s), ring(rings - 1, s + 1)
        out.append("f %d//%d %d//%d %d//%d" % (a, a, south, south, b, b))
    assert n == south
    write(path, out)


def grid(path, n=200):
    out = ["# %dx%d quad height field, no normals" % (n, n)]
    for j in range(n + 1):
        for i in range(n + 1):
            x, z = -1 + 2.0 * i / n, -1 + 2.0 * j / n
            y = 0.12 * math.sin(4 * x + 1) * math.cos(3 * z) + 0.05 * math.sin(11 * x * z)
            out.append("v %.9f %.9f %.9f" % (x, y, z))
    for j in range(n):
        for i in range(n):
            a = 1 + j * (n + 1) + i
            b, c, d = a + n + 1, a + n + 2, a + 1  # CCW seen from +y
            if (i + j) % 7 == 3:
                out.append("f %d %d %d" % (a, b, c))   # some faces as explicit triangles,
                out.append("f %d %d %d" % (a, c, d))   # with negative indices below
            elif (i + j) % 11 == 5:
                out.append("f %d %d %d %d" % (-(n + 1) ** 2 - 1 + a, -(n + 1) ** 2 - 1 + b,
                                              -(n + 1) ** 2 - 1 + c, -(n + 1) ** 2 - 1 + d))
            else:
                out.append("f %d %d %d %d" % (a, b, c, d))
    write(path, out)


def ground(path):
    write(path, ["# ground quad, repeated uvs",
                 "v -50 0 50", "v 50 0 50", "v 50 0 -50", "v -50 0 -50",
                 "vt 0 0", "vt 50 0", "vt 50 50", "vt 0 50", "vn 0 1 0",
                 "f 1/1/1 2/2/1 3/3/1 4/4/1"])


def huge(path):
    write(path, ["# triangles with 1e6 coordinates",
                 "v -1e6 -1 1e6", "v 1e6 -1 1e6", "v 0 -1 -1e6",
                 "v -1e6 -1e6 -60", "v 1e6 -1e6 -60", "v 0 1e6 -60.5",
                 "vn 0 1 0", "vn 0 0 1",
                 "f 1//1 2//1 3//1", "f 4//2 5//2 6//2",
                 # a small box-ish object near the camera to share the depth range
                 "v -0.5 -1 -2", "v 0.5 -1 -2", "v 0 0.6 -2.5",
                 "f 7 8 9"])


def ppm(path, w, h, pixel):
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (w, h))
        f.write(bytes(c for y in range(h) for x in range(w) for c in pixel(x, y)))


def tie(path, tex_path, size=64, tex=32):
    """Mosaic of 4x4-pixel cells; vertices at half-integer world coordinates = pixel centres.
    Cells are split along either diagonal, into 4 around the cell centre, or left empty, with
    random winding, so every edge direction and both windings meet centres on their edges."""
    rnd = random.Random(1234)
    half = size // 2
    verts, faces, uvs = [], [], []
    texels = list(range(tex * tex))
    rnd.shuffle(texels)

    def v(x, y):
        verts.append("v %.1f %.1f 0" % (x - half, y - half))
        return len(verts)

    def tri(a, b, c):
        t = texels[len(faces) % len(texels)]
        uvs.append("vt %.9f %.9f" % (((t % tex) + 0.5) / tex, ((t // tex) + 0.5) / tex))
        k = len(uvs)
        order = [a, b, c] if rnd.random() < 0.5 else [a, c, b]
        faces.append("f " + " ".join("%d/%d" % (q, k) for q in order))

    cell = 4
    for cy in range(size // cell):
        for cx in range(size // cell):
            x0, y0 = cx * cell + 0.5, cy * cell + 0.5
            x1, y1 = x0 + cell, y0 + cell
            if x1 > size or y1 > size:  # keep the last row/column of centres for edges
                x1, y1 = min(x1, size - 0.5), min(y1, size - 0.5)
            a, b, c, d = v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y1)
            kind = rnd.randrange(6)
            if kind == 0:
                continue  # empty: edges against the background
            if kind == 1:
                tri(a, b, c), tri(a, c, d)
            elif kind == 2:
                tri(a, b, d), tri(b, c, d)
            elif kind == 3:
                m = v((x0 + x1) / 2, (y0 + y1) / 2)
                tri(a, b, m), tri(b, c, m), tri(c, d, m), tri(d, a, m)
            elif kind == 4:  # slopes 1/2 and 2 through the mid-points of the sides
                m1, m2 = v((x0 + x1) / 2, y0), v(x1, (y0 + y1) / 2)
                tri(a, m1, d), tri(m1, c, d), tri(m1, b, m2), tri(m1, m2, c)
            else:  # long thin sliver pair, slope 1/4
                m = v(x0, (y0 + y1) / 2)
                tri(a, b, m), tri(m, b, c), tri(m, c, d)
    write(path, ["# tie-rule mosaic"] + verts + uvs + faces)

    def colour(x, y):
        i = y * tex + x
        r, g, b = 40 + (i * 37) % 200, 40 + (i * 91) % 200, 40 + (i * 53) % 200
        return (r, g, b)
    ppm(tex_path, tex, tex, colour)


def grid_stl(obj_path, stl_path):
    """Binary STL of an OBJ's faces (fanned (0, i, i+1)), normals from the winding. STL is
    Z-up (the 3D-printing convention rastty follows): the Y-up OBJ's point (x, y, z) is
    stored as (x, -z, y), which rastty turns back to (x, y, z) exactly (a swap and a sign)."""
    pos, tris = [], []
    for line in open(obj_path):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            pos.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "f":
            idx = [int(c.split("/")[0]) for c in w[1:]]
            idx = [i - 1 if i > 0 else len(pos) + i for i in idx]
            for k in range(1, len(idx) - 1):
                tris.append((idx[0], idx[k], idx[k + 1]))
    out = bytearray(b"binary STL of " + os.path.basename(obj_path).encode())
    out += b"\0" * (80 - len(out))
    out += struct.pack("<I", len(tris))
    for a, b, c in tris:
        p0, p1, p2 = pos[a], pos[b], pos[c]
        u = [p1[i] - p0[i] for i in range(3)]
        v = [p2[i] - p0[i] for i in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        out += struct.pack("<3f", n[0], -n[2], n[1])
        for p in (p0, p1, p2):
            out += struct.pack("<3f", p[0], -p[2], p[1])
        out += b"\0\0"
    with open(stl_path, "wb") as f:
        f.write(out)


def png_bytes(w, h, pixel):
    raw = b"".join(b"\0" + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def globe(d, seg=48, rings=24):
    """A textured UV sphere twice: globe.obj in world coordinates, globe.glb in local ones
    under a node transform. Same vertices, same triangles, same texture."""
    local = []  # (position, normal, uv)
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(seg + 1):
            ph = 2 * math.pi * s / seg
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            local.append((n, n, (s / seg, 1 - r / rings)))
    tris = []
    for r in range(rings):
        for s in range(seg):
            a, b = r * (seg + 1) + s, (r + 1) * (seg + 1) + s
            if r > 0:
                tris.append((a, b, a + 1))
            if r < rings - 1:
                tris.append((a + 1, b, b + 1))
    ang, scale, move = math.radians(30), 0.8, (0.1, 0.05, 0.0)
    c, s_ = math.cos(ang), math.sin(ang)

    def rot(v):  # about +Y
        return (c * v[0] + s_ * v[2], v[1], -s_ * v[0] + c * v[2])

    # float32 first, so both files hold the same numbers before the transform
    f32 = lambda x: struct.unpack("<f", struct.pack("<f", x))[0]
    local = [(tuple(map(f32, p)), tuple(map(f32, n)), tuple(map(f32, t))) for p, n, t in local]
    lines = ["# textured sphere (globe.glb's node transform applied)", "mtllib globe.mtl"]
    for p, n, t in local:
        q = rot(tuple(scale * x for x in p))
        lines.append("v %.9f %.9f %.9f" % tuple(q[i] + move[i] for i in range(3)))
    for p, n, t in local:
        lines.append("vn %.9f %.9f %.9f" % rot(n))
    for p, n, t in local:
        lines.append("vt %.9f %.9f" % t)
    lines.append("usemtl globe")
    for a, b, cc in tris:
        lines.append("f %d/%d/%d %d/%d/%d %d/%d/%d" % (a + 1, a + 1, a + 1, b + 1, b + 1, b + 1,
                                                       cc + 1, cc + 1, cc + 1))
    write(os.path.join(d, "globe.obj"), lines)
    write(os.path.join(d, "globe.mtl"), ["newmtl globe", "Kd 1 1 1", "map_Kd globe.png"])
    png = png_bytes(32, 16, lambda x, y: (230, 200, 60) if ((x // 4) + (y // 4)) % 2 else
                    (40 + 5 * x, 60 + 9 * y, 160))
    with open(os.path.join(d, "globe.png"), "wb") as f:
        f.write(png)
    # glTF binary: one buffer holding positions, normals, uvs (v flipped), indices, the PNG
    posb = b"".join(struct.pack("<3f", *p) for p, n, t in local)
    nrmb = b"".join(struct.pack("<3f", *n) for p, n, t in local)
    uvb = b"".join(struct.pack("<2f", t[0], 1 - t[1]) for p, n, t in local)
    idxb = b"".join(struct.pack("<3I", *t) for t in tris)
    views, blob = [], b""
    for part in (posb, nrmb, uvb, idxb, png):
        blob += b"\0" * (-len(blob) % 4)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(part)})
        blob += part
    blob += b"\0" * (-len(blob) % 4)
    nv = len(local)
    lo = [min(p[i] for p, n, t in local) for i in range(3)]
    hi = [max(p[i] for p, n, t in local) for i in range(3)]
    gl = {
        "asset": {"version": "2.0", "generator": "rastty gen_models.py"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "placed", "children": [1], "translation": list(move)},
                  {"mesh": 0, "rotation": [0, math.sin(ang / 2), 0, math.cos(ang / 2)],
                   "scale": [scale] * 3}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                    "indices": 3, "material": 0}]}],
        # roughness 0.4925: rastty's Blinn-Phong exponent 32, the OBJ twin's Ns (light.h:
        # n = 2 / r^4 - 2); a dielectric's highlight then has ks 0.484 against the MTL's 0.5
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1],
                                                "baseColorTexture": {"index": 0},
                                                "metallicFactor": 0, "roughnessFactor": 0.4925}}],
        "textures": [{"source": 0}],
        "images": [{"bufferView": 4, "mimeType": "image/png"}],
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": nv, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": 3 * len(tris), "type": "SCALAR"},
        ],
    }
    js = json.dumps(gl).encode()
    js += b" " * (-len(js) % 4)
    glb = (struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(js) + 8 + len(blob))
           + struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(blob), b"BIN\0") + blob)
    with open(os.path.join(d, "globe.glb"), "wb") as f:
        f.write(glb)


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "build/oracle/models"
    os.makedirs(d, exist_ok=True)
    sphere(os.path.join(d, "sphere.obj"))
    grid(os.path.join(d, "grid.obj"))
    ground(os.path.join(d, "ground.obj"))
    huge(os.path.join(d, "huge.obj"))
    tie(os.path.join(d, "tie.obj"), os.path.join(d, "tie.ppm"))
    grid_stl(os.path.join(d, "grid.obj"), os.path.join(d, "grid.stl"))
    globe(d)
    ppm(os.path.join(d, "checker.ppm"), 64, 64,
        lambda x, y: (230, 200, 60) if ((x // 8) + (y // 8)) % 2 else
        (40 + 3 * x, 60 + 2 * y, 140))


if __name__ == "__main__":
    main()
