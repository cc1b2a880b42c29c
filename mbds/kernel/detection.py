"""Contact detection between polygon shapes: vertices of one body against edges of another.

Shapes are closed counter-clockwise polygons in body frames (m); a body's world pose is
(x, y, Rz) in (m, m, rad). For a vertex P of body V and an edge Q0 -> Q1 of body E, with
tangent t = (Q1 - Q0) / L and outward normal n = (t_y, -t_x) of E:

- position along the edge xi = t . (P - Q0) / L, a candidate when 0 <= xi <= 1 (or within the
  edge's :func:`band` beyond a concave corner);
- gap g = n . (P - Q0) (m), negative in penetration; a candidate when -skin_E < g <= margin.

Past the end Q1 of an edge where the outline turns convexly (a convex corner C = Q1, the next
edge running from C), a vertex in the corner's exterior wedge (beyond the ends of both edges)
faces neither edge. Within the margin of C it is a corner contact: gap |P - C| (at least
CORNER_GAP x maxPen), normal (P - C) / |P - C| (the bisector of the two edges' normals when P is
closer than that), xi of the edge that ends at C (> 1). Corner contacts are always open: they
take part in no impact and no contact LCP, and serve the step control, which trusts every
vertex within the margin of the other body to be reported (mbds.kernel.motion.reach_limit).

A vertex deeper than DEEP x skin behind an edge counts only if it lies inside the edge's body
(a point-in-polygon test), and of a vertex's contacts with one body behind their faces only those
within DEEP x skin of the nearest of them are kept: where the skin is thicker than a body, a
vertex near one face is also within the skin of the opposite face, seen from inside, without
touching it. Contacts in front of their faces are all kept: in the notch at a concave corner a
vertex is in front of both faces, and the nearer one is the one it approaches.

Which vertex-edge directions are tested follows ``resistingPenetration``: a body that resists
penetration has its edges tested against the other body's vertices (T:T both ways).

Broad phase: for each pair, the axis-aligned boxes of the two shapes are intersected (the edge
body's box inflated by its skin and the margin); only vertices inside the overlap and edges
crossing it are kept, and where there are more than FEW_EDGES of them they are bucketed along
the overlap's longer side, so the cost grows with the number of points near the contact, not
with the product of the point counts. Each kept edge's unit tangent and length are computed
once; a vertex's gap is tested before its position along the edge.
"""

from __future__ import annotations

import numpy as np

from mbds.kernel.jit import jit

FEW_EDGES = 16
"""Up to this many edges near a pair's overlap, every vertex tests each of them: sorting them
into buckets would cost more."""
CORNER_GAP = 0.3
"""The smallest gap of a corner contact (x maxPen): above the gap up to which a contact at rest is
held (mbds.kernel.contact_problem.HELD_FRACTION), so that a corner contact is never closed. The
step control lets an approaching open contact go at most half maxPen past its gap, so a vertex
this near a corner ends a step at most 0.8 maxPen inside the corner's body."""
DEEP = 0.01
"""A vertex deeper than DEEP x skin behind a face (with the default skin: deeper than
maximumPenetration) is in contact with it only if it lies inside the face's body, and a vertex's
contacts with one body behind their faces are those within DEEP x skin of the nearest of them."""


@jit(refcount=False)
def world_points(pose, trig, points, point_start, out):
    """Body-frame ``points`` (P, 2) of every body moved to the world by ``pose`` (nb, 3), with
    trig (nb, 2) the cosine and sine of each body's angle."""
    for b in range(pose.shape[0]):
        c, s = trig[b, 0], trig[b, 1]
        for i in range(point_start[b], point_start[b + 1]):
            _world_point(pose, b, c, s, points, i, out)


@jit(inline="always")
def _world_point(pose, b, c, s, points, i, out):
    """out[i] = point i of body b moved to the world (c, s: cos and sin of its angle)."""
    x, y = points[i, 0], points[i, 1]
    out[i, 0] = pose[b, 0] + c * x - s * y
    out[i, 1] = pose[b, 1] + s * x + c * y


@jit(refcount=False)
def contact_points(pose, trig, points, c_vertex_body, c_vertex, c_edge_body, c_edge, index, count, out):
    """The world points (into ``out``, as :func:`world_points` computes them) of the vertex and
    the edge's two points of the contacts index[:count]; the other points are left as they
    are."""
    for k in range(count):
        i = index[k]
        b = c_vertex_body[i]
        _world_point(pose, b, trig[b, 0], trig[b, 1], points, c_vertex[i], out)
        b = c_edge_body[i]
        _world_point(pose, b, trig[b, 0], trig[b, 1], points, c_edge[i], out)
        _world_point(pose, b, trig[b, 0], trig[b, 1], points, c_edge[i] + 1, out)


@jit(refcount=False)
def bounding_boxes(world, point_start, out):
    """Axis-aligned box (xmin, ymin, xmax, ymax) of each body's world points into out (nb, 4)."""
    for b in range(point_start.shape[0] - 1):
        x0, y0, x1, y1 = np.inf, np.inf, -np.inf, -np.inf
        for i in range(point_start[b], point_start[b + 1]):
            x0 = min(x0, world[i, 0])
            y0 = min(y0, world[i, 1])
            x1 = max(x1, world[i, 0])
            y1 = max(y1, world[i, 1])
        out[b, 0] = x0
        out[b, 1] = y0
        out[b, 2] = x1
        out[b, 3] = y1


@jit(refcount=False)
def detect_contacts(
    world, point_start, point_reflex, concave, boxes, pair_bodies, pair_resisting, skin, margin, max_pen,
    c_pair, c_vertex_body, c_vertex, c_edge_body, c_edge, c_xi, c_gap, c_normal, c_point, work, frames,
):
    """Find vertex-edge and vertex-corner contacts of all pairs; return their count, or -1 if the
    output arrays (capacity ``c_pair.shape[0]``) are too small.

    world: (P, 2) world points from :func:`world_points`; point_reflex: (P,) whether the outline
    turns clockwise at each point (mbds.model.arrays.concave_corners) and concave: (nb,) whether a
    body has such a point; boxes: (nb, 4) from
    :func:`bounding_boxes`; pair_bodies: (np, 2); pair_resisting: (np, 2) booleans;
    skin: (nb,) deepest penetration checked (m); margin: (np,) largest positive gap reported
    per pair (m); max_pen: maximumPenetration (m), which sets the smallest gap of a corner
    contact (CORNER_GAP).
    Outputs per contact: pair, vertex body and (global) point index, edge body and the global
    index of the edge's first point, xi, gap (m), outward normal of the edge (2,), vertex
    position (2,). work: int64 scratch of at least 3 * P + 2050 entries; frames: (P, 5) scratch
    for the unit tangent, length and band (:func:`band`) of each edge near a pair's overlap (row:
    its first point).
    """
    count = 0
    capacity = c_pair.shape[0]
    for p in range(pair_bodies.shape[0]):
        for side in range(2):
            edge_body = pair_bodies[p, side]
            vertex_body = pair_bodies[p, 1 - side]
            if not pair_resisting[p, side]:
                continue
            reach = skin[edge_body] + margin[p]
            # (a vertex facing an edge beyond a concave corner lies within 2 reach of that corner)
            x0, y0, x1, y1 = _overlap(boxes, vertex_body, edge_body, 2.0 * reach if concave[edge_body] else reach)
            if x0 > x1 or y0 > y1:  # no vertex can be near an edge
                continue
            count = _pair_contacts(
                p, vertex_body, edge_body, world, point_start, point_reflex, concave[edge_body], x0, y0, x1, y1,
                skin[edge_body], margin[p], CORNER_GAP * max_pen, c_pair, c_vertex_body, c_vertex, c_edge_body, c_edge,
                c_xi, c_gap, c_normal, c_point, work, frames, count, capacity,
            )
            if count < 0:
                return -1
    return count


@jit(inline="always")
def _overlap(boxes, vb, eb, reach):
    """(x0, y0, x1, y1): the part of the vertex body's box within ``reach`` (m) of the edge
    body's box; empty (x0 > x1 or y0 > y1) when they are farther apart."""
    return (max(boxes[vb, 0], boxes[eb, 0] - reach), max(boxes[vb, 1], boxes[eb, 1] - reach),
            min(boxes[vb, 2], boxes[eb, 2] + reach), min(boxes[vb, 3], boxes[eb, 3] + reach))


@jit(refcount=False)
def _pair_contacts(
    p, vb, eb, world, point_start, point_reflex, concave, x0, y0, x1, y1, skin, margin, corner_gap,
    c_pair, c_vertex_body, c_vertex, c_edge_body, c_edge, c_xi, c_gap, c_normal, c_point,
    work, frames, count, capacity,
):
    """Contacts of the vertices of body vb in the box (x0, y0, x1, y1) against the edges of
    body eb (see :func:`detect_contacts`; concave: whether eb has a concave corner; corner_gap:
    the smallest gap of a corner contact, m); return the new count, or -1 when full."""
    reach = skin + margin
    npts = world.shape[0]
    edges = npts  # work layout (no array views): vertices, edges, bucket starts, bucket members
    starts = 2 * npts
    members = 2 * npts + 1025
    nv = 0
    for i in range(point_start[vb], point_start[vb + 1] - 1):
        if x0 <= world[i, 0] <= x1 and y0 <= world[i, 1] <= y1:
            work[nv] = i
            nv += 1
    if nv == 0:
        return count
    ne = 0
    for j in range(point_start[eb], point_start[eb + 1] - 1):
        ex0, ex1 = min(world[j, 0], world[j + 1, 0]), max(world[j, 0], world[j + 1, 0])
        ey0, ey1 = min(world[j, 1], world[j + 1, 1]), max(world[j, 1], world[j + 1, 1])
        pad = _pad(point_reflex, j, reach) if concave else reach
        if ex1 + pad >= x0 and ex0 - pad <= x1 and ey1 + pad >= y0 and ey0 - pad <= y1:
            work[edges + ne] = j
            ne += 1
            _edge_frame(world, point_reflex, j, reach, frames)
    if ne == 0:
        return count
    # bucket the edges along the longer side of the overlap box (up to FEW_EDGES stay in one bucket)
    axis = 0 if (x1 - x0) >= (y1 - y0) else 1
    lo = x0 if axis == 0 else y0
    span = (x1 - x0) if axis == 0 else (y1 - y0)
    nb = min(ne, 1024)
    if span <= 0.0 or ne <= FEW_EDGES:
        nb = 1
    width = span / nb if nb > 1 else 1.0
    for k in range(nb + 1):
        work[starts + k] = 0
    room = work.shape[0] - members
    for pass_ in range(2):
        if pass_ == 1:
            total = 0
            for k in range(nb):
                c = work[starts + k]
                work[starts + k] = total
                total += c
            work[starts + nb] = total
            if total > room:  # too many bucket entries: one bucket with every edge
                nb = 1
                work[starts] = 0
                work[starts + 1] = ne
                for e in range(ne):
                    work[members + e] = work[edges + e]
                break
        for e in range(ne):
            j = work[edges + e]
            pad = _pad(point_reflex, j, reach) if concave else reach
            a = min(world[j, axis], world[j + 1, axis]) - pad
            b = max(world[j, axis], world[j + 1, axis]) + pad
            for k in range(_bucket(a, lo, width, nb), _bucket(b, lo, width, nb) + 1):
                if pass_ == 0:
                    work[starts + k] += 1
                else:
                    work[members + work[starts + k]] = j
                    work[starts + k] += 1
        if pass_ == 1:
            for k in range(nb, 0, -1):
                work[starts + k] = work[starts + k - 1]
            work[starts] = 0
    for v in range(nv):
        i = work[v]
        first = count
        k = _bucket(world[i, axis], lo, width, nb)
        for m in range(work[starts + k], work[starts + k + 1]):
            j = work[members + m]
            tx, ty, length = frames[j, 0], frames[j, 1], frames[j, 2]
            gap = _gap(world, i, j, tx, ty)
            if gap <= -reach or gap > margin:  # (in a corner's exterior wedge, within the margin of both lines)
                continue
            xi = _xi(world, i, j, tx, ty, length)
            if xi > 1.0 and not point_reflex[j + 1]:  # past a convex end: a corner contact or none
                nx, ny, gap = _corner(world, i, j, tx, ty, point_start[eb], point_start[eb + 1], margin, corner_gap)
                if gap > margin:
                    continue
            else:
                if gap <= -skin or xi < frames[j, 3] or xi > frames[j, 4]:  # (within a band beyond a concave end)
                    continue
                nx, ny = ty, -tx
            if gap < -DEEP * skin and not _inside(world, i, point_start[eb], point_start[eb + 1]):
                continue  # within the skin of a face seen from inside, but outside the body
            if count >= capacity:
                return -1
            c_pair[count] = p
            c_vertex_body[count] = vb
            c_vertex[count] = i
            c_edge_body[count] = eb
            c_edge[count] = j
            c_xi[count] = xi
            c_gap[count] = gap
            c_normal[count, 0] = nx
            c_normal[count, 1] = ny
            c_point[count, 0] = world[i, 0]
            c_point[count, 1] = world[i, 1]
            count += 1
        count = _nearest_faces(first, count, DEEP * skin, c_vertex, c_edge, c_xi, c_gap, c_normal, c_point)
    return count


@jit(inline="always")
def _corner(world, i, j, tx, ty, start, stop, margin, corner_gap):
    """(n_x, n_y, gap) of world point i against the convex corner C = point j + 1 at the end of the
    edge from point j (unit tangent (tx, ty)), for a point past that end: the gap is |P - C| (at
    least ``corner_gap``, m) where P lies in the corner's exterior wedge within ``margin`` (m) of C,
    else inf. start, stop: the edge body's points (the last one repeats the first)."""
    c = j + 1
    following = _next_edge(j, start, stop) + 1  # the far end of the edge that starts at C
    dx, dy = world[i, 0] - world[c, 0], world[i, 1] - world[c, 1]
    ux, uy = world[following, 0] - world[c, 0], world[following, 1] - world[c, 1]
    d2 = dx * dx + dy * dy
    if dx * ux + dy * uy >= 0.0 or d2 > margin * margin:  # facing the next edge, or too far
        return 0.0, 0.0, np.inf
    distance = np.sqrt(d2)
    if distance > corner_gap:
        return dx / distance, dy / distance, distance
    # nearer than the smallest gap: the bisector of the two outward normals (or, where the
    # outline turns back on itself, the direction beyond the end)
    u = np.sqrt(ux * ux + uy * uy)
    bx, by = ty + uy / u, -tx - ux / u
    size = np.sqrt(bx * bx + by * by)
    if size < 1e-9:
        return tx, ty, corner_gap
    return bx / size, by / size, corner_gap


@jit(inline="always")
def _next_edge(j, start, stop):
    """The edge (its first point) after the edge from point j of a body whose points are
    start ... stop - 1, the last repeating the first."""
    return j + 1 if j + 1 < stop - 1 else start


@jit(inline="always")
def _previous_edge(j, start, stop):
    """The edge (its first point) before the edge from point j (see :func:`_next_edge`)."""
    return j - 1 if j > start else stop - 2


@jit(inline="always")
def _nearest_faces(first, count, tolerance, c_vertex, c_edge, c_xi, c_gap, c_normal, c_point):
    """Of one vertex's contacts with one body (rows first ... count - 1), keep every one in front
    of its face (gap > 0) and, of those behind their faces, the ones whose gap is within
    ``tolerance`` (m) of the nearest (the largest gap behind a face); return the new count. A
    vertex on one face of a body thinner than the skin also lies within the skin of the
    opposite face, seen from inside: that face is not in contact. A vertex in front of two faces
    (in the notch at a concave corner) may touch either."""
    if count - first < 2:
        return count
    best = -np.inf
    for r in range(first, count):
        if c_gap[r] <= 0.0:
            best = max(best, c_gap[r])
    kept = first
    for r in range(first, count):
        if c_gap[r] > 0.0 or c_gap[r] >= best - tolerance:
            if kept != r:
                c_vertex[kept] = c_vertex[r]
                c_edge[kept] = c_edge[r]
                c_xi[kept] = c_xi[r]
                c_gap[kept] = c_gap[r]
                c_normal[kept, 0] = c_normal[r, 0]
                c_normal[kept, 1] = c_normal[r, 1]
                c_point[kept, 0] = c_point[r, 0]
                c_point[kept, 1] = c_point[r, 1]
            kept += 1
    return kept


@jit(inline="always")
def _inside(world, i, start, stop):
    """Whether world point i lies inside the closed polygon of points start ... stop - 1 (the
    last one repeats the first): the crossing number of a ray towards +x."""
    x, y = world[i, 0], world[i, 1]
    inside = False
    for j in range(start, stop - 1):
        ax, ay, bx, by = world[j, 0], world[j, 1], world[j + 1, 0], world[j + 1, 1]
        if (ay > y) != (by > y) and x < ax + (y - ay) * (bx - ax) / (by - ay):
            inside = not inside
    return inside


@jit(inline="always")
def _bucket(value, lo, width, nb):
    if nb == 1:
        return 0
    k = int((value - lo) / width)
    return min(max(k, 0), nb - 1)


@jit(inline="always")
def vertex_edge(world, i, j):
    """(xi, gap, n_x, n_y) of world point i against the edge from point j to point j + 1."""
    tx, ty, length = _frame(world, j)
    return _xi(world, i, j, tx, ty, length), _gap(world, i, j, tx, ty), ty, -tx


@jit(inline="always")
def _xi(world, i, j, tx, ty, length):
    """xi of world point i along the edge from point j with unit tangent (tx, ty) and length (m)."""
    return (tx * (world[i, 0] - world[j, 0]) + ty * (world[i, 1] - world[j, 1])) / length


@jit(inline="always")
def _gap(world, i, j, tx, ty):
    """The gap (m) of world point i from the edge from point j with unit tangent (tx, ty)."""
    return ty * (world[i, 0] - world[j, 0]) - tx * (world[i, 1] - world[j, 1])


@jit(inline="always")
def _frame(world, j):
    """(t_x, t_y, L): the unit tangent and the length (m) of the edge from point j to j + 1."""
    tx, ty = world[j + 1, 0] - world[j, 0], world[j + 1, 1] - world[j, 1]
    length = np.sqrt(tx * tx + ty * ty)
    return tx / length, ty / length, length


@jit(inline="always")
def _edge_frame(world, point_reflex, j, reach, frames):
    """frames[j] = :func:`_frame` of edge j and its :func:`band`."""
    frames[j, 0], frames[j, 1], frames[j, 2] = _frame(world, j)
    frames[j, 3], frames[j, 4] = band(point_reflex, j, reach, frames[j, 2])


@jit(inline="always")
def _pad(point_reflex, j, reach):
    """How far (m) from the edge from point j to j + 1, along either axis, a vertex facing it
    can be: ``reach``, or twice that where its :func:`band` reaches beyond a concave corner."""
    return 2.0 * reach if point_reflex[j] or point_reflex[j + 1] else reach


@jit(inline="always")
def band(point_reflex, j, reach, length):
    """(lo, hi): the range of xi over which a vertex faces the edge from point j to j + 1 of
    ``length`` (m): [0, 1], reaching ``reach`` (m: the pair's skin plus its detection margin)
    beyond an end at a concave corner. There the bands of the two edges that meet leave a
    wedge that neither covers: a vertex sliding along one face a little behind it, or moving
    towards the other face from before its start, would reach the other face unseen, within a
    step that the step control (which trusts every vertex within reach of an edge to be
    detected) does not shorten."""
    lo = -reach / length if point_reflex[j] else 0.0
    hi = 1.0 + reach / length if point_reflex[j + 1] else 1.0
    return lo, hi


@jit(refcount=False)
def contact_geometry(world, c_vertex, c_edge, index, count, c_xi, c_gap, c_normal, c_point):
    """Recompute xi, gap, normal and point of the known vertex-edge contacts index[:count] at
    new world points."""
    for c in range(count):
        k = index[c]
        i = c_vertex[k]
        c_xi[k], c_gap[k], c_normal[k, 0], c_normal[k, 1] = vertex_edge(world, i, c_edge[k])
        c_point[k, 0] = world[i, 0]
        c_point[k, 1] = world[i, 1]


@jit(refcount=False)
def tracked_depth(world, point_start, point_reflex, skin, margin, contacts, count):
    """The deepest penetration (m) at the world points ``world`` of the first ``count`` known
    contacts; 0 if none penetrates. Unlike detection, this sees a vertex however deep it went.

    A vertex is as deep as it is behind its edge while it faces it (xi within the :func:`band` of
    their detection: skin (nb,) and margin (np,) in m). Near an end of its edge where the outline
    turns convexly, it may also face the other edge that meets there: then it is as deep as
    it is behind the nearer of the two (it entered through the other one), and past that end,
    as deep as it is behind the other edge where it lies inside the body (it passed the corner).
    Each of these is at least its distance from the outline, so no penetration is underrated."""
    depth = 0.0
    for k in range(count):
        i, j, eb = contacts.vertex[k], contacts.edge[k], contacts.eb[k]
        tx, ty, length = _frame(world, j)
        gap = _gap(world, i, j, tx, ty)
        if -gap <= depth:  # no deeper than found so far (past a convex end, the other edge is nearer)
            continue
        xi = _xi(world, i, j, tx, ty, length)
        lo, hi = band(point_reflex, j, skin[eb] + margin[contacts.pair[k]], length)
        facing = lo <= xi <= hi
        deeper = -gap if facing else 0.0
        end = j + 1 if xi > 0.5 else j
        if not point_reflex[end]:
            start, stop = point_start[eb], point_start[eb + 1]
            other = _next_edge(j, start, stop) if end == j + 1 else _previous_edge(j, start, stop)
            ox, oy, other_length = _frame(world, other)
            if 0.0 <= _xi(world, i, other, ox, oy, other_length) <= 1.0 and tx * ox + ty * oy > -1.0 + 1e-12:
                behind = -_gap(world, i, other, ox, oy)  # (not where the outline turns back: a shape of two points)
                if facing:
                    deeper = min(deeper, behind)
                elif behind > depth and _inside(world, i, start, stop):
                    deeper = behind
        depth = max(depth, deeper)
    return depth
