#!/usr/bin/python3
"""objs_to_pc2.py OUT.pc2 FRAME.obj...: the frames' `v` lines as one PC2 point cache (frames 1..N,
rate 1), written as Blender's exporter writes one: the farm tests' shot as a cache."""
import struct
import sys

frames = [[tuple(map(float, line.split()[1:4])) for line in open(path) if line.startswith("v ")]
          for path in sys.argv[2:]]
with open(sys.argv[1], "wb") as out:
    out.write(struct.pack("<12siiffi", b"POINTCACHE2\0", 1, len(frames[0]), 1.0, 1.0, len(frames)))
    for vertices in frames:
        out.write(b"".join(struct.pack("<3f", *p) for p in vertices))
