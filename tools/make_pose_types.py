#!/usr/bin/env python3
"""Writes data/configurations/pose-types.jsonl: 24 configurations of the kinds issue 12 names
(see data/configurations/README.md), for `surfgrav interact --batch`.

Run from the repository root: `python3 tools/make_pose_types.py`. Deterministic (random
attitudes of the triaxial pairs from random.seed(7)); two 3-D offsets that overlapped in the
first draft were moved apart (line 12 by hand, line 13 by two 15 % steps), as recorded below.
"""
import json
import math
import random

random.seed(7)
OBLATE = "spheroid:equatorial=1,polar=0.5,mass=1"
PROLATE = "spheroid:equatorial=0.5,polar=1,mass=1"
SMALL_OBLATE = "spheroid:equatorial=0.8,polar=0.3,mass=0.7"
DISK = "disk:radius=1,mass=1"
TRIAXIAL_A = "ellipsoid:a=1,b=0.7,c=0.5,mass=1"
TRIAXIAL_B = "ellipsoid:a=0.8,b=0.6,c=0.4,mass=0.6"

lines = []


def add(a, b, position, orientation_a=None, orientation_b=None):
    d = {"a": a, "b": b, "position": position}
    if orientation_a:
        d["orientation_a"] = orientation_a
    if orientation_b:
        d["orientation_b"] = orientation_b
    lines.append(d)


for x in (2.1, 2.55, 3, 7, 30):
    add(OBLATE, OBLATE, [x, 0, 0])
add(OBLATE, OBLATE, [0, 0, 1.1])
add(PROLATE, PROLATE, [0, 0, 2.1])
add(OBLATE, PROLATE, [0, 0, 1.6])
add(OBLATE, OBLATE, [0.3, 0, 1.15])
add(OBLATE, SMALL_OBLATE, [0.4, 0.2, 0.95])
add(PROLATE, PROLATE, [0.5, 0.3, 2.05])
add(OBLATE, PROLATE, [1.45, 0.8, 0.6])  # first draft [1.1, 0.6, 0.5] overlapped
add(OBLATE, PROLATE, [x * 1.15 * 1.15 for x in (0.9, -0.7, 0.9)], None, [0.3, 0.5, 0.1])
add(SMALL_OBLATE, PROLATE, [1.2, 0.4, -0.6], [0.2, -0.1, 0.4], [1.0, 0.2, 0.3])
add(OBLATE, DISK, [0, 0, 0.6])
add(OBLATE, DISK, [0.4, 0.3, 0.65])
add(OBLATE, DISK, [0.2, 0, 0.9], None, [0.4, 0, 0])
add(PROLATE, DISK, [0, 0, 1.2])
for _ in range(6):
    v = [random.uniform(-1, 1) for _ in range(3)]
    n = math.sqrt(sum(t * t for t in v))
    v = [t / n for t in v]
    d = 2.0 + random.uniform(0.05, 1.0)
    oa = [random.uniform(-1.5, 1.5) for _ in range(3)]
    ob = [random.uniform(-1.5, 1.5) for _ in range(3)]
    add(TRIAXIAL_A, TRIAXIAL_B, [d * t for t in v], oa, ob)

with open("data/configurations/pose-types.jsonl", "w") as f:
    for d in lines:
        f.write(json.dumps(d) + "\n")
