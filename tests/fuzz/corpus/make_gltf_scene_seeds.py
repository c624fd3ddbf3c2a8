#!/usr/bin/env python3
"""Writes the gltf_scene fuzz seeds that probe the scene-file sandbox and the texture checks (standard library
only): URIs that are absolute or climb out of the scene's folder (plain and percent-encoded); a textured
triangle whose embedded PNG (in a buffer view, and as a data: URI) declares 20000x20000 pixels in a header of
45 bytes; one whose PNG's IDAT chunk declares 1 GiB in a file of a few hundred bytes (stb_image allocated it
before finding the bytes missing); one whose valid PNG's buffer view runs past the end of its buffer (the bytes
are in the file, past the buffer's byteLength), also with the view named by an index past 32 bits; and one whose
texture is a BMP that stb_image would decode (glTF textures are PNG or JPEG; stb_image's other decoders are kept
from hostile bytes). Run from this folder: python3 make_gltf_scene_seeds.py"""
import base64
import json
import struct
import zlib


def chunk(kind, data, declared=None):
    length = len(data) if declared is None else declared
    return struct.pack(">I", length) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png_header_claiming(width, height):
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)  # 8-bit grey: stb_image decodes it (to RGBA, 1.6 GB)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", b"\x78\x01")


def png_idat_claiming(declared):
    ihdr = struct.pack(">IIBBBBB", 1, 1, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", b"\x78\x01", declared)


def png_one_pixel():
    ihdr = struct.pack(">IIBBBBB", 1, 1, 8, 6, 0, 0, 0)  # 8-bit RGBA
    pixels = zlib.compress(b"\x00\xff\x80\x00\xff")  # one row: filter byte, then RGBA
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", pixels) + chunk(b"IEND", b"")


def bmp_one_pixel():
    pixels = b"\x00\x00\xff\x00"  # one red BGR pixel, its row padded to 4 bytes
    info = struct.pack("<IiiHHIIiiII", 40, 1, 1, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
    return b"BM" + struct.pack("<IHHI", 14 + len(info) + len(pixels), 0, 0, 14 + len(info)) + info + pixels


def glb(document, binary=b""):
    text = json.dumps(document, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text
    if binary:
        binary += b"\0" * (-len(binary) % 4)
        chunks += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def textured_triangle(image):
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uvs = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    geometry = positions + uvs
    document = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [image],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
        ],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
        "buffers": [{"byteLength": len(geometry)}],
    }
    return document, geometry


def triangle_with_embedded_texture(image, image_bytes_in_buffer=None, view_index=2):
    """The textured triangle as a .glb whose texture is `image` in a buffer view after the geometry (view 2, named
    as `view_index`); the buffer's byteLength covers `image_bytes_in_buffer` of it (all by default), though the
    file holds all of it."""
    document, geometry = textured_triangle({"bufferView": view_index, "mimeType": "image/png"})
    document["bufferViews"].append({"buffer": 0, "byteOffset": len(geometry), "byteLength": len(image)})
    covered = len(image) if image_bytes_in_buffer is None else image_bytes_in_buffer
    document["buffers"][0]["byteLength"] = len(geometry) + covered
    return glb(document, geometry + image)


def main():
    seeds = {
        "absolute_buffer_uri.glb": glb({"asset": {"version": "2.0"}, "buffers": [{"uri": "/etc/hostname", "byteLength": 4}]}),
        "escaping_image_uri.glb": glb({"asset": {"version": "2.0"}, "images": [{"uri": "../outside.png"}]}),
        "encoded_escaping_image_uri.glb": glb({"asset": {"version": "2.0"}, "images": [{"uri": "..%2Foutside.png"}]}),
    }
    png = png_header_claiming(20000, 20000)
    seeds["oversized_texture.glb"] = triangle_with_embedded_texture(png)
    document, geometry = textured_triangle({"uri": "data:image/png;base64," + base64.b64encode(png).decode()})
    seeds["oversized_data_uri_texture.glb"] = glb(document, geometry)
    seeds["oversized_png_chunk.glb"] = triangle_with_embedded_texture(png_idat_claiming(2**30 - 16))
    # The buffer ends two bytes into the pixel data: the decoder copies the rest from past the buffer's end.
    png = png_one_pixel()
    covered = png.index(b"IDAT") + 4 + 2
    seeds["image_view_past_buffer.glb"] = triangle_with_embedded_texture(png, covered)
    # The same view named as 2^32 + 2, which tinygltf cuts to 32 bits: view 2.
    seeds["image_view_index_past_32_bits.glb"] = triangle_with_embedded_texture(png, covered, 2**32 + 2)
    seeds["bmp_texture.glb"] = triangle_with_embedded_texture(bmp_one_pixel())
    for name, data in seeds.items():
        with open("gltf_scene/" + name, "wb") as out:
            out.write(data)


if __name__ == "__main__":
    main()
