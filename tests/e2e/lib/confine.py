#!/usr/bin/env python3
"""confine.py DIR: glTF models in DIR/model whose buffer or image names a file outside that
folder in every way a download could (issue 25 item 19), and one that stays inside.

DIR/secret.bin and DIR/secret.png lie beside the model's folder. Each DIR/model/NAME.gltf
is a white quad (unlit); its buffer URI is NAME's case below (a broken buffer is an error), except
img_*.gltf, whose buffer is inside and whose base colour texture names the secret image
(a texture that cannot be read is a warning). DIR/model/link.bin is a symbolic link to the
secret buffer, DIR/model/up a link to DIR, DIR/model/in.bin the buffer itself."""
import base64, json, os, struct, sys, zlib

D = sys.argv[1]
M = os.path.join(D, "model")
os.makedirs(os.path.join(M, "tex"), exist_ok=True)
quad = struct.pack("<12f", -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0)
uv = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
BIN = quad + uv + idx


def png(w, h, rgb):
    raw = b"".join(b"\x00" + bytes(rgb) * w for _ in range(h))
    def chunk(t, b):
        return struct.pack(">I", len(b)) + t + b + struct.pack(">I", zlib.crc32(t + b))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def gltf(buffer_uri, image_uri=None):
    g = {"asset": {"version": "2.0"},
         "buffers": [{"byteLength": len(BIN), "uri": buffer_uri}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                         {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                         {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                        "min": [-1, -1, 0], "max": [1, 1, 0]},
                       {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                       {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
         "scenes": [{"nodes": [0]}], "scene": 0, "nodes": [{"mesh": 0}],
         "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]},
                        "extensions": {"KHR_materials_unlit": {}}}],
         "extensionsUsed": ["KHR_materials_unlit"],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1},
                                     "indices": 2, "material": 0}]}]}
    if image_uri:
        g["images"] = [{"uri": image_uri}]
        g["textures"] = [{"source": 0}]
        g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    return json.dumps(g)


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


write(os.path.join(D, "secret.bin"), BIN)
write(os.path.join(D, "secret.png"), png(4, 4, (0, 255, 0)))
write(os.path.join(M, "in.bin"), BIN)
for name, target in (("link.bin", os.path.join(D, "secret.bin")), ("up", D),
                     ("link.png", os.path.join(D, "secret.png"))):
    p = os.path.join(M, name)
    if os.path.lexists(p):
        os.remove(p)
    os.symlink(target, p)
secret = os.path.join(os.path.abspath(D), "secret")
cases = {
    "dotdot": "../secret.bin",
    "absolute": secret + ".bin",
    "file_uri": "file://" + secret + ".bin",
    "file_relative": "file:../secret.bin",
    "percent_slash": "..%2Fsecret.bin",
    "percent_dots": "%2e%2e/secret.bin",
    "percent_all": "%2E%2E%2F%73ecret.bin",
    "deep": "tex/../../secret.bin",
    "link": "link.bin",
    "dir_link": "up/secret.bin",
    "inside": "in.bin",
}
for name, uri in cases.items():
    write(os.path.join(M, name + ".gltf"), gltf(uri).encode())
for name, uri in {"img_dotdot": "../secret.png", "img_absolute": secret + ".png",
                  "img_link": "link.png", "img_percent": "..%2Fsecret.png"}.items():
    write(os.path.join(M, name + ".gltf"), gltf("in.bin", uri).encode())
