#!/usr/bin/env python3
"""Extracts MediaPipe's canonical 3D face (468 vertices, Apache-2.0) from the
npm package @mediapipe/face_mesh and writes it as text: one "x y z" line per
vertex, in MediaPipe's metric face space (cm; x to the face's left as seen by
the camera, y up, z towards the camera).

The package packs its assets into face_mesh_solution_packed_assets.data; the
loader script lists each file's byte range. The file wanted,
geometry_pipeline_metadata_landmarks.binarypb, is a protocol buffer: its
field 1 is the canonical mesh (field 2 the Procrustes basis, field 3 the input
source), and the mesh's field 3 holds the vertex floats, five per vertex
(x y z u v), packed or one by one. Only the wire format is needed to read it.
"""
import argparse
import json
import re
import struct
import sys

ASSET = "geometry_pipeline_metadata_landmarks.binarypb"
VERTICES = 468


def varint(data, pos):
    value = shift = 0
    while True:
        byte = data[pos]
        pos += 1
        value |= (byte & 0x7F) << shift
        if not byte & 0x80:
            return value, pos
        shift += 7


def fields(data):
    """Yields (field number, wire type, value) of a serialized message."""
    pos = 0
    while pos < len(data):
        key, pos = varint(data, pos)
        number, wire = key >> 3, key & 7
        if wire == 0:
            value, pos = varint(data, pos)
        elif wire == 1:
            value, pos = data[pos:pos + 8], pos + 8
        elif wire == 2:
            length, pos = varint(data, pos)
            value, pos = data[pos:pos + length], pos + length
        elif wire == 5:
            value, pos = data[pos:pos + 4], pos + 4
        else:
            raise ValueError(f"unsupported wire type {wire}")
        yield number, wire, value


def canonical_vertices(loader_js, packed_data):
    ranges = {m.group(1): (int(m.group(2)), int(m.group(3))) for m in re.finditer(
        r'"filename":\s*"([^"]+)",\s*"start":\s*(\d+),\s*"end":\s*(\d+)', loader_js)}
    name = next((n for n in ranges if n.endswith(ASSET)), None)
    if name is None:
        raise ValueError(f"the loader lists no {ASSET}")
    start, end = ranges[name]
    metadata = packed_data[start:end]
    mesh = next((v for n, w, v in fields(metadata) if n == 1 and w == 2), None)
    if mesh is None:
        raise ValueError("no canonical_mesh in the metadata")
    floats = b"".join(v for n, w, v in fields(mesh) if n == 3 and w in (2, 5))
    values = struct.unpack(f"<{len(floats) // 4}f", floats)
    if len(values) != VERTICES * 5:
        raise ValueError(f"vertex_buffer has {len(values)} floats, expected {VERTICES * 5} (x y z u v)")
    return [values[5 * i:5 * i + 3] for i in range(VERTICES)]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("package_dir", help="the unpacked npm package (its package/ folder)")
    parser.add_argument("out", help="text file to write")
    args = parser.parse_args()
    try:
        with open(f"{args.package_dir}/face_mesh_solution_packed_assets_loader.js") as f:
            loader = f.read()
        with open(f"{args.package_dir}/face_mesh_solution_packed_assets.data", "rb") as f:
            packed = f.read()
        with open(f"{args.package_dir}/package.json") as f:
            licence = json.load(f).get("license", "?")
        vertices = canonical_vertices(loader, packed)
    except (OSError, ValueError, IndexError, struct.error) as e:
        print(f"extract_canonical_face: {e}", file=sys.stderr)
        return 1
    with open(args.out, "w") as f:
        f.write(f"# MediaPipe canonical face, {VERTICES} vertices, cm (x y z); from @mediapipe/face_mesh ({licence})\n")
        for x, y, z in vertices:
            f.write(f"{x:.6f} {y:.6f} {z:.6f}\n")
    print(f"extract_canonical_face: wrote {VERTICES} vertices to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
