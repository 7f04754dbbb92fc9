#!/usr/bin/python3
"""The friction threshold of a planar structure of rigid blocks: the smallest
Coulomb coefficient at which the blocks can stand in equilibrium.

Rigid-block limit analysis (Livesley 1978; Gilbert, Casapulla and Ahmed
2006), static form. The structure is read from a scenario file: every body
a box or hull that is a prism along z (the scene is a planar one extruded
in depth) and turned, if at all, about z only; gravity in the x-y plane.
Two bodies touch where an edge of one's x-y outline lies on an edge of the
other's with the opposite outward normal; the interface is the overlap of
the two edges. Unknowns: a normal force n >= 0 and a tangential force t at
each end of each interface (two end forces carry any resultant inside the
interface: no tension). Each dynamic body is in equilibrium under them and
its weight (two forces and the moment about its centroid); a static body
takes whatever it is given. Friction: |t| <= mu n at every end.

In the extruded 3D scene the same holds: a 3D equilibrium mirrored in z
and averaged with itself is a planar one whose in-plane tangential force is
no larger, and a planar one extruded is a 3D one with no out-of-plane
force, so the 3D cone |t| <= mu n reduces exactly to the planar one.

For a fixed mu the conditions are linear, so "an equilibrium exists" is an
LP feasibility question (scipy's HiGHS); it is monotone in mu (a solution
at mu is one at any larger mu), so the threshold is found by bisection.
Below it no equilibrium exists and the blocks must move; at or above it
staying at rest is a consistent motion (Coulomb friction is not
associative, so the static theorem does not promise it is the only one).

Usage: arch_friction_threshold.py SCENARIO.json   prints the threshold.
The threshold of a scene with one friction for every body is independent of
density and |g| (every force scales with them).
"""
import json
import math
import sys

from scipy.optimize import linprog

GEOMETRY_TOLERANCE = 1e-6  # m: two edges closer than this are one interface (the file's numbers agree to 1e-15)
MU_CEILING = 100.0  # above this a structure "stands at no friction" in any useful sense
MU_RESOLUTION = 1e-7  # bisection stops when the bracket is this narrow (well inside the 4 printed decimals)


def fail(message):
    sys.exit(f"arch_friction_threshold: {message}")


def rotation_about_z(body, where):
    """The angle of a body's orientation, which must turn about z only."""
    orientation = body.get("orientation")
    if orientation is None:
        return 0.0
    if "quaternion" in orientation:
        w, x, y, z = orientation["quaternion"]
        if abs(x) > 1e-12 or abs(y) > 1e-12:
            fail(f"{where}: turned about an axis other than z; the analysis is planar")
        return 2.0 * math.atan2(z, w)
    ax, ay, az = orientation["axis"]
    if abs(ax) > 1e-12 or abs(ay) > 1e-12:
        fail(f"{where}: turned about an axis other than z; the analysis is planar")
    return orientation["angle"] if az > 0 else -orientation["angle"]


def convex_outline(points):
    """Counter-clockwise convex hull of 2D points (monotone chain), no collinear points."""
    pts = sorted(set(points))

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 1e-12:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 1e-12:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def polygon_area_centroid(poly):
    area = cx = cy = 0.0
    for i, (x0, y0) in enumerate(poly):
        x1, y1 = poly[(i + 1) % len(poly)]
        c = x0 * y1 - x1 * y0
        area += c
        cx += (x0 + x1) * c
        cy += (y0 + y1) * c
    area *= 0.5
    return area, (cx / (6.0 * area), cy / (6.0 * area))


def body_outline(body, where):
    """The body's x-y outline in world coordinates and its depth along z."""
    shape = body["shape"]
    if shape["kind"] == "box":
        hx, hy, hz = shape["halfExtents"]
        local = [(sx * hx, sy * hy, sz * hz) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    elif shape["kind"] == "hull":
        local = [tuple(p) for p in shape["points"]]
    else:
        fail(f"{where}: a {shape['kind']} has no flat faces; only boxes and hulls")
    zs = sorted({round(p[2], 9) for p in local})
    if len(zs) != 2:
        fail(f"{where}: not a prism along z (points at {len(zs)} depths)")
    front = {(round(p[0], 12), round(p[1], 12)) for p in local if abs(p[2] - zs[0]) < 1e-9}
    back = {(round(p[0], 12), round(p[1], 12)) for p in local if abs(p[2] - zs[1]) < 1e-9}
    if front != back:
        fail(f"{where}: its front and back outlines differ; not a prism along z")
    angle = rotation_about_z(body, where)
    c, s = math.cos(angle), math.sin(angle)
    px, py = body["position"][0], body["position"][1]
    world = [(px + c * x - s * y, py + s * x + c * y) for x, y in front]
    return convex_outline(world), zs[1] - zs[0]


def load_structure(path):
    with open(path) as f:
        scenario = json.load(f)
    if scenario.get("sweeps"):
        fail(f"{path}: has sweeps; give one resolved scene")
    gravity = scenario.get("world", {}).get("gravity", [0.0, -9.81, 0.0])
    if abs(gravity[2]) > 1e-12:
        fail(f"{path}: gravity has a z component; the analysis is planar")
    blocks = []
    for index, body in enumerate(scenario["bodies"]):
        where = f"{path}: /bodies/{index} ({body['name']})"
        if body["motion"] == "kinematic":
            fail(f"{where}: a kinematic body; only static and dynamic ones")
        outline, depth = body_outline(body, where)
        area, centroid = polygon_area_centroid(outline)
        mass = 0.0
        if body["motion"] == "dynamic":
            mass = body["mass"] if "mass" in body else body["density"] * area * depth
        blocks.append({"name": body["name"], "dynamic": body["motion"] == "dynamic", "outline": outline,
                       "centroid": centroid, "weight": (mass * gravity[0], mass * gravity[1]),
                       "friction": body.get("friction", 0.5)})
    return scenario, blocks


def edges(outline):
    for i, a in enumerate(outline):
        b = outline[(i + 1) % len(outline)]
        length = math.hypot(b[0] - a[0], b[1] - a[1])
        tangent = ((b[0] - a[0]) / length, (b[1] - a[1]) / length)
        yield a, tangent, length, (tangent[1], -tangent[0])  # outward normal of a counter-clockwise outline


def find_interfaces(blocks):
    """Each touching pair of edges: (A, B, normal from A into B, tangent, [two end points])."""
    found = []
    for ia in range(len(blocks)):
        for ib in range(ia + 1, len(blocks)):
            if not (blocks[ia]["dynamic"] or blocks[ib]["dynamic"]):
                continue
            for a0, ta, la, na in edges(blocks[ia]["outline"]):
                for b0, _, lb, nb in edges(blocks[ib]["outline"]):
                    if na[0] * nb[0] + na[1] * nb[1] > -1 + 1e-9:
                        continue  # not facing each other
                    d = (b0[0] - a0[0], b0[1] - a0[1])
                    if abs(d[0] * na[0] + d[1] * na[1]) > GEOMETRY_TOLERANCE:
                        continue  # parallel but apart
                    # B's edge runs against A's: from s - lb to s along A's tangent.
                    s = d[0] * ta[0] + d[1] * ta[1]
                    lo, hi = max(0.0, s - lb), min(la, s)
                    if hi - lo <= GEOMETRY_TOLERANCE:
                        continue
                    ends = [(a0[0] + u * ta[0], a0[1] + u * ta[1]) for u in (lo, hi)]
                    found.append((ia, ib, na, ta, ends))
    return found


def equilibrium_exists(blocks, interfaces, mu):
    """LP feasibility: end forces (n >= 0, |t| <= mu n) holding every dynamic block."""
    dynamic = [i for i, b in enumerate(blocks) if b["dynamic"]]
    row_of = {body: 3 * k for k, body in enumerate(dynamic)}
    scale = max(math.hypot(*blocks[i]["weight"]) for i in dynamic)  # forces in units of the heaviest weight
    variables = 2 * sum(len(f[4]) for f in interfaces)
    a_eq = [[0.0] * variables for _ in range(3 * len(dynamic))]
    b_eq = [0.0] * (3 * len(dynamic))
    for body in dynamic:
        wx, wy = blocks[body]["weight"]
        b_eq[row_of[body]] = -wx / scale
        b_eq[row_of[body] + 1] = -wy / scale
    a_ub, b_ub = [], []
    column = 0
    for ia, ib, normal, tangent, ends in interfaces:
        for point in ends:
            for var, direction in ((column, normal), (column + 1, tangent)):
                # The force on B is +direction per unit, on A its opposite.
                for body, sign in ((ib, 1.0), (ia, -1.0)):
                    if body not in row_of:
                        continue
                    cx, cy = blocks[body]["centroid"]
                    fx, fy = sign * direction[0], sign * direction[1]
                    r = row_of[body]
                    a_eq[r][var] += fx
                    a_eq[r + 1][var] += fy
                    a_eq[r + 2][var] += (point[0] - cx) * fy - (point[1] - cy) * fx
            for sign in (1.0, -1.0):  # +-t - mu n <= 0
                row = [0.0] * variables
                row[column + 1] = sign
                row[column] = -mu
                a_ub.append(row)
                b_ub.append(0.0)
            column += 2
    bounds = [(0, None) if v % 2 == 0 else (None, None) for v in range(variables)]
    result = linprog([0.0] * variables, A_ub=a_ub, b_ub=b_ub, A_eq=a_eq, b_eq=b_eq, bounds=bounds,
                     method="highs")
    if result.status not in (0, 2):
        fail(f"the LP solver stopped: {result.message}")
    return result.status == 0


def friction_threshold(blocks, interfaces):
    """The least mu with an equilibrium, or None when none exists below MU_CEILING."""
    if not equilibrium_exists(blocks, interfaces, MU_CEILING):
        return None
    lo, hi = 0.0, MU_CEILING
    if equilibrium_exists(blocks, interfaces, 0.0):
        return 0.0
    while hi - lo > MU_RESOLUTION:
        mid = 0.5 * (lo + hi)
        if equilibrium_exists(blocks, interfaces, mid):
            hi = mid
        else:
            lo = mid
    return hi


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: arch_friction_threshold.py SCENARIO.json")
    path = sys.argv[1]
    scenario, blocks = load_structure(path)
    interfaces = find_interfaces(blocks)
    dynamic = sum(1 for b in blocks if b["dynamic"])
    print(f"{scenario['name']}: {dynamic} dynamic blocks, {len(interfaces)} interfaces")
    threshold = friction_threshold(blocks, interfaces)
    if threshold is None:
        print(f"no equilibrium at any friction up to {MU_CEILING:g}")
        return
    print(f"friction threshold mu* = {threshold:.4f}")
    frictions = {b["friction"] for b in blocks}
    if len(frictions) == 1:
        mu = frictions.pop()
        print(f"file's friction {mu:g} = {mu / threshold:.2f} x the threshold" if threshold > 0 else
              f"file's friction {mu:g}")


if __name__ == "__main__":
    main()
