#!/usr/bin/env python3
"""Writes the glTF test asset textured_quad.gltf (+ .bin, two PNGs, .scene.json, and all of it but the scene
description as one textured_quad.glb) into this folder.

A 2 m x 2 m quad facing +Z, its base-color texture split into four coloured quadrants (red top left, green top
right, blue bottom left, yellow bottom right), a flat normal map (tangents left to the loader to generate), a
perspective camera 3 m in front of it and a KHR_lights_punctual sun shining onto it from above the camera. Standard library
only; run it again to regenerate the committed files: python3 tests/data/make_textured_quad.py
"""
import json
import struct
import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent
QUADRANTS = {(0, 0): (220, 40, 40), (1, 0): (40, 200, 60), (0, 1): (40, 60, 220), (1, 1): (230, 210, 40)}


def png(width, height, pixel):
    """RGBA8 PNG; pixel(x, y) -> (r, g, b, a), row 0 on top."""
    rows = b"".join(b"\0" + b"".join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def write_glb(gltf, blob):
    """The same scene as one binary file (textured_quad.glb): buffer and both PNGs in its BIN chunk."""
    gltf = json.loads(json.dumps(gltf))
    data = bytearray(blob)
    for index, image in enumerate(gltf["images"]):
        png_bytes = (HERE / image.pop("uri")).read_bytes()
        gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(png_bytes)})
        image.update({"bufferView": len(gltf["bufferViews"]) - 1, "mimeType": "image/png"})
        data += png_bytes + b"\0" * (-len(png_bytes) % 4)  # chunk and views 4-byte aligned
    gltf["buffers"] = [{"byteLength": len(data)}]
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(data), b"BIN\0") + bytes(data)
    (HERE / "textured_quad.glb").write_bytes(struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)


def main():
    size = 8
    (HERE / "textured_quad_base_color.png").write_bytes(
        png(size, size, lambda x, y: QUADRANTS[(x * 2 // size, y * 2 // size)] + (255,)))
    (HERE / "textured_quad_normal.png").write_bytes(png(size, size, lambda x, y: (128, 128, 255, 255)))

    # Corners counter-clockwise seen from +Z; texture v = 0 at the top edge.
    positions = [(-1, 1, 0), (1, 1, 0), (1, -1, 0), (-1, -1, 0)]
    normals = [(0, 0, 1)] * 4
    uvs = [(0, 0), (1, 0), (1, 1), (0, 1)]
    indices = [3, 2, 1, 3, 1, 0]
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    blob += b"".join(struct.pack("<3f", *n) for n in normals)
    blob += b"".join(struct.pack("<2f", *t) for t in uvs)
    blob += struct.pack("<6H", *indices)  # 140 bytes: a multiple of 4 as GLB chunks need
    (HERE / "textured_quad.bin").write_bytes(blob)

    gltf = {
        "asset": {"version": "2.0", "generator": "s3d tests/data/make_textured_quad.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "color": [1, 1, 1], "intensity": 1.2}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "quad", "mesh": 0},
            {"name": "camera", "camera": 0, "translation": [0, 0, 3]},
            # Shines down its -Z, turned 30 degrees about X: onto the quad from above the camera.
            {"name": "sun", "rotation": [-0.258819, 0, 0, 0.965926], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 100}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [{"name": "quadrants",
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0,
                                                "roughnessFactor": 0.8},
                       "normalTexture": {"index": 1}}],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729}],
        "images": [{"uri": "textured_quad_base_color.png"}, {"uri": "textured_quad_normal.png"}],
        "buffers": [{"uri": "textured_quad.bin", "byteLength": len(blob)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
            {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    }
    (HERE / "textured_quad.gltf").write_text(json.dumps(gltf, indent=1) + "\n")
    write_glb(gltf, blob)
    # What glTF does not carry: ambient light, sky and exposure.
    description = {"ambient": [0.2, 0.2, 0.2], "exposure": 1.0, "ambientOcclusion": False,
                   "sky": {"zenith": [0.02, 0.02, 0.02], "horizon": [0.02, 0.02, 0.02], "ground": [0.02, 0.02, 0.02]}}
    (HERE / "textured_quad.scene.json").write_text(json.dumps(description, indent=1) + "\n")


if __name__ == "__main__":
    main()
