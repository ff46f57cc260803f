#!/usr/bin/env python3
"""Writes projects/olinda/models/turbine.gltf: a three-bladed wind turbine (80 m hub,
40 m blades) as glTF 2.0 with one embedded buffer and three named nodes that Sylva's
`objects` source can turn: `tower` (root), `nacelle` (child of tower, at the hub height;
turns about its +Y = up: yaw) and `rotor` (child of nacelle, 3 m forward; its node is
turned so its +Y is the rotor axis: `rotor_angle` spins the blades).

glTF frame: +Y up, +Z forward, metres. Run: python3 scripts/make-turbine-model.py
"""
import base64
import json
import math
import struct
import sys

HUB = 80.0
BLADE = 40.0


def box(x0, x1, y0, y1, z0, z1):
    corners = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    faces = [((0, 0, -1), [0, 2, 6, 4]), ((0, 0, 1), [1, 5, 7, 3]), ((-1, 0, 0), [0, 1, 3, 2]),
             ((1, 0, 0), [4, 6, 7, 5]), ((0, -1, 0), [0, 4, 5, 1]), ((0, 1, 0), [2, 3, 7, 6])]
    return quads(corners, faces)


def quads(corners, faces):
    positions, normals, indices = [], [], []
    for normal, quad in faces:
        base = len(positions)
        for i in quad:
            positions.append(corners[i])
            normals.append(normal)
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return positions, normals, indices


def tower():
    """An octagonal tube tapering from 2.2 m to 1.4 m radius, 0 .. HUB - 1.5 m."""
    positions, normals, indices = [], [], []
    sides = 8
    top = HUB - 1.5
    for i in range(sides):
        a0, a1 = 2 * math.pi * i / sides, 2 * math.pi * (i + 1) / sides
        mid = 0.5 * (a0 + a1)
        n = (math.sin(mid), 0.0, math.cos(mid))
        base = len(positions)
        for a, r, y in ((a0, 2.2, 0.0), (a1, 2.2, 0.0), (a1, 1.4, top), (a0, 1.4, top)):
            positions.append((r * math.sin(a), y, r * math.cos(a)))
            normals.append(n)
        indices += [base, base + 2, base + 1, base, base + 3, base + 2]
    return positions, normals, indices


def rotor():
    """Hub box and three blades in the node's XZ plane (the node's +Y is the rotor axis)."""
    positions, normals, indices = box(-1.5, 1.5, -1.5, 1.5, -1.5, 1.5)
    for k in range(3):
        angle = math.pi / 2 + 2 * math.pi * k / 3
        d = (math.cos(angle), 0.0, math.sin(angle))
        s = (-d[2], 0.0, d[0])  # across the blade, in the rotor plane
        corners = []
        for along, half in ((1.5, 1.2), (BLADE, 0.3)):
            for side in (-1, 1):
                for y in (-0.25, 0.25):
                    corners.append((d[0] * along + s[0] * half * side, y,
                                    d[2] * along + s[2] * half * side))
        faces = [((0, -1, 0), [0, 4, 6, 2]), ((0, 1, 0), [1, 3, 7, 5]),
                 ((s[0], 0, s[2]), [2, 6, 7, 3]), ((-s[0], 0, -s[2]), [0, 1, 5, 4]),
                 ((d[0], 0, d[2]), [4, 5, 7, 6])]
        p, n, i = quads(corners, faces)
        base = len(positions)
        positions += p
        normals += n
        indices += [base + j for j in i]
    return positions, normals, indices


def main(path):
    meshes = [("tower", tower()), ("nacelle", box(-1.5, 1.5, -1.5, 1.5, -6.0, 2.0)),
              ("rotor", rotor())]
    data = bytearray()
    views, accessors, gltf_meshes = [], [], []
    for index, (name, (positions, normals, indices)) in enumerate(meshes):
        for kind, values in (("POSITION", positions), ("NORMAL", normals)):
            offset = len(data)
            for v in values:
                data += struct.pack("<3f", *v)
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data) - offset,
                          "target": 34962})
            accessor = {"bufferView": len(views) - 1, "componentType": 5126,
                        "count": len(values), "type": "VEC3"}
            if kind == "POSITION":
                accessor["min"] = [min(v[i] for v in values) for i in range(3)]
                accessor["max"] = [max(v[i] for v in values) for i in range(3)]
            accessors.append(accessor)
        offset = len(data)
        for i in indices:
            data += struct.pack("<I", i)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data) - offset,
                      "target": 34963})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125,
                          "count": len(indices), "type": "SCALAR"})
        gltf_meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": 3 * index, "NORMAL": 3 * index + 1},
            "indices": 3 * index + 2, "material": 0 if name != "rotor" else 1}]})
    s = math.sqrt(0.5)
    gltf = {
        "asset": {"version": "2.0", "generator": "scripts/make-turbine-model.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"name": "tower", "mesh": 0, "children": [1]},
            {"name": "nacelle", "mesh": 1, "translation": [0, HUB, 0], "children": [2]},
            {"name": "rotor", "mesh": 2, "translation": [0, 0, 3.0], "rotation": [s, 0, 0, s]},
        ],
        "meshes": gltf_meshes,
        "materials": [
            {"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.78, 1]}},
            {"name": "blades", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1]}},
        ],
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(bytes(data)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(path, "w") as out:
        json.dump(gltf, out, indent=1)
        out.write("\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "projects/olinda/models/turbine.gltf")
