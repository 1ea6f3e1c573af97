"""One block of the distributed triangulation: its points, the ghosts around them and the global
hull's extreme points, triangulated together; which of the simplices are final; which the block
owns; what it sends the others.

The rule (docs/design-notes.md, "Distributed Delaunay on Dask" and "A block is sent the borders
of the others"):

* In the first round a block's *local* points are its own points, every other point in its
  region (its cell grown by the ghost width, a closed box, tested exactly) or in the strips
  along the sides of the bounding box, and the extreme points of the global hull. The local
  points therefore have the global hull, and every point that is not local lies in the global
  bounding box strictly outside the region and the strips, in a bin where the count of all
  points exceeds the count of the local ones.
* A local simplex is *final* when no outside point can lie in its closed circumball: the ball
  misses every slab of the bounding box beyond the region, or the box round its part inside
  the bounding box and the hull meets those slabs only inside the strips, or the ball's part in
  that box meets no bin with an outside point; by margins that cover the rounding of centre and
  radius. Then it is a simplex of the global triangulation: the perturbation depends on the
  points alone, so the local points decide it as all do.
* The block is *done* when every simplex with one of its own points as a vertex is final: the
  stars of its points are then exactly the global stars.
* Every block, done or not, sends each other block its *border* for it: its own points that
  are vertices of a local simplex whose closed circumball meets that block's cell (or of a hull
  face whose plane does). The centre of a global ball through an own point q lies in q's
  Voronoi cell among the local points, so the ball lies in the union of the local balls round
  q (and of the half-spaces beyond q's hull faces): every point of this block in a global star
  of another block is in its border for that block.
* A block not done in the first round is triangulated again with its own points, the hull's
  points and the borders the others sent it; its stars are then the global ones without a test
  (every vertex they need is there), so there are at most two rounds.
* Each simplex is *owned* by the block that owns its vertex first along the Hilbert curve of
  the points' bounding box (ties: the lowest index; ``_curve_order``), an order every block
  sees alike, so exactly one block outputs it. Its neighbour across a face is final where it
  has an own vertex; across the faces where the neighbour is owned elsewhere, the two owners of
  a face find each other by the face (``match_faces``), so no block needs the neighbours of its
  stars.
"""
import numpy as np

from .. import _core
from ..spatial import Delaunay
from ._blocks import Grid

_EPS = float(np.finfo(np.float64).eps)


def _quiet():
    """NumPy's warnings off for divisions by zero and infinities, which are expected here."""
    return np.errstate(divide="ignore", invalid="ignore", over="ignore")


# The centre of a simplex whose condition number passes this is not trusted: it is not final.
_MAX_CONDITION = 1e10
# Simplices tested at a time (the temporaries: about 1 KB a simplex).
_PIECE = 1 << 22
# Simplices times hull planes beyond which the caps along the hull planes are not computed (the
# test stays sound without them, only coarser): a block of points on a sphere has as many
# planes as points, and every simplex to test. Counted over the balls the caps over their own
# hull faces leave uncovered (final_simplices): 2-4 of about 1 400 per block tested in NumPy
# for 2·10^6 uniform points in 4 blocks.
_CAP_WORK = 1 << 28


def _circumcentres(pts, s):
    """Circumcentres, radii and an upper bound of their rounding error, for simplices ``s``.

    The centre solves ``A x = b`` (rows of A: the edges from the first vertex, b: half their
    squared lengths) by the adjugate; the error bound is a generous multiple of
    eps * cond(A) * |x| (cond from the Frobenius norms of A and its adjugate). Where the
    determinant is zero or the condition is beyond ``_MAX_CONDITION`` the bound is infinite."""
    p0 = pts[s[:, 0]]
    a = pts[s[:, 1:]] - p0[:, None, :]
    rhs = 0.5 * np.einsum("mij,mij->mi", a, a)
    if pts.shape[1] == 2:
        det = a[:, 0, 0] * a[:, 1, 1] - a[:, 0, 1] * a[:, 1, 0]
        cols = np.stack([np.stack([a[:, 1, 1], -a[:, 1, 0]], 1),
                         np.stack([-a[:, 0, 1], a[:, 0, 0]], 1)], 1)
    else:
        c0 = np.cross(a[:, 1], a[:, 2])
        cols = np.stack([c0, np.cross(a[:, 2], a[:, 0]), np.cross(a[:, 0], a[:, 1])], 1)
        det = np.einsum("mi,mi->m", a[:, 0], c0)
    with _quiet():
        x = np.einsum("mi,mij->mj", rhs, cols) / det[:, None]
        radius = np.sqrt(np.einsum("mi,mi->m", x, x))
        cond = (np.sqrt(np.einsum("mij,mij->m", a, a))
                * np.sqrt(np.einsum("mij,mij->m", cols, cols)) / np.abs(det))
        edge = np.sqrt(np.einsum("mij,mij->mi", a, a).max(axis=1))
        err = 1e3 * _EPS * cond * (radius + edge)
    bad = ~np.isfinite(x).all(axis=1) | ~(cond < _MAX_CONDITION)
    err[bad] = np.inf
    x[bad] = 0.0
    return p0 + x, radius, err


def _slabs(region_lo, region_hi, box_lo, box_hi):
    """The boxes where points outside the region may lie: the bounding box beyond the region,
    one slab per axis and side that has room."""
    out = []
    for k in range(len(box_lo)):
        if region_lo[k] > box_lo[k]:
            hi = box_hi.copy()
            hi[k] = region_lo[k]
            out.append((box_lo.copy(), hi))
        if region_hi[k] < box_hi[k]:
            lo = box_lo.copy()
            lo[k] = region_hi[k]
            out.append((lo, box_hi.copy()))
    return out


def _ball_misses(centre, reach, slabs):
    ok = np.isfinite(reach)
    for lo, hi in slabs:
        gap = np.maximum(np.maximum(lo - centre, centre - hi), 0.0)
        ok &= np.sqrt(np.einsum("mi,mi->m", gap, gap)) > reach
    return ok


def _covered(klo, khi, slabs, extras):
    """Whether the part of each box (klo, khi) in every slab is empty or inside an extra box."""
    ok = np.ones(len(klo), dtype=bool)
    for lo, hi in slabs:
        plo, phi = np.maximum(klo, lo), np.minimum(khi, hi)
        inside = np.any(plo > phi, axis=1)  # empty
        for elo, ehi in extras:
            inside |= np.all((plo >= elo) & (phi <= ehi), axis=1)
        ok &= inside
    return ok


def _ball_in_box(centre, reach, lo, hi):
    """The exact bounding box of each ball's part in the box [lo, hi] (empty: lo > hi). Along
    axis k, x_k = t is reachable where (t - c_k)^2 plus the squared distance to the box in the
    other axes (which does not depend on t) is at most r^2."""
    gap = np.maximum(np.maximum(lo - centre, centre - hi), 0.0) ** 2
    other = gap.sum(axis=1)[:, None] - gap
    half = np.sqrt(np.maximum(reach[:, None] ** 2 - other, 0.0))
    blo, bhi = np.maximum(centre - half, lo), np.minimum(centre + half, hi)
    blo[other > reach[:, None] ** 2] = np.inf  # misses the box
    return blo, bhi


def _furthest_plane(count, planes, heights):
    """For each of ``count`` centres, the hull plane it lies furthest beyond and how far:
    ``heights(i, j)`` gives centres i:j's signed heights over every plane (rows by planes),
    computed a slice of rows at a time (at most 64 MiB of heights)."""
    best = np.zeros(count, dtype=np.int64)
    top = np.zeros(count)
    step = max(1, (1 << 23) // len(planes))
    for i in range(0, count, step):
        h = heights(i, i + step)
        best[i:i + step] = np.argmax(h, axis=1)
        top[i:i + step] = h[np.arange(len(h)), best[i:i + step]]
    return best, top


def _hull_cap(centre, reach, planes):
    """Where a ball's centre lies beyond a hull plane (outward unit normal n, offset t: inside
    n.x + t <= 0), the hull's points in the ball lie in the cap on the inner side of the plane
    furthest behind the centre: the disc of radius sqrt(r^2 - h^2) round the centre's foot on
    the plane, swept inwards by the cap's depth r - h. Returns the box round the cap (the
    ball's box where there is no cut) and the caps' slabs (``_cap_slab``)."""
    best, hb = _furthest_plane(
        len(centre), planes, lambda i, j: centre[i:j] @ planes[:, :-1].T + planes[:, -1])
    cut = (hb > 0) & (hb < reach)
    n = planes[best, :-1]
    foot = centre - hb[:, None] * n
    rim = np.sqrt(np.maximum(reach * reach - hb * hb, 0.0))
    lo, hi = _cap_box(foot, n, rim, -(reach - hb))
    lo = np.where(cut[:, None], lo, centre - reach[:, None])
    hi = np.where(cut[:, None], hi, centre + reach[:, None])
    at = np.nonzero(cut)[0]
    return lo, hi, [(at,) + _cap_slab(foot[at], n[at], -(reach - hb)[at])]


def _face_caps(pts, t, nbt):
    """Boxes round the part inside the hull of the circumballs of simplices ``t`` that have a
    face on the hull (no neighbour in ``nbt``) with the centre beyond it, computed from that
    face, without the centre (which is far and ill-conditioned for the flat simplices along
    the hull).

    The spheres through a face F (circumcentre p, radius rho, unit normal n towards the
    opposite vertex q, h = (q - p).n) have centres p + t n, and the one through q has
    t = w / 2h, w = |q - p|^2 - rho^2: the centre is beyond F exactly when q lies inside F's
    diametral sphere (w < 0). The ball's part on q's side (the hull's side: F is a hull facet)
    is then the cap over F's circumdisc of depth rho^2 / (r + |t|) <= rho^2 h / |w|, a bound
    that stays accurate however far the centre is. Returns the boxes (lo, hi), unbounded where
    no face applies, and the caps' slabs (``_cap_slab``)."""
    m, d1 = t.shape
    d = d1 - 1
    lo = np.full((m, d), -np.inf)
    hi = np.full((m, d), np.inf)
    cuts = []
    for j in range(d1):
        face = nbt[:, j] < 0
        if not bool(face.any()):
            continue
        rows = np.nonzero(face)[0]
        p, n, rho, h, w, ew, span, good = _face_sphere(pts, t[rows], j)
        with _quiet():
            depth = rho * rho * (h * (1 + 1e-9) + 1e-12 * span) / (-w - ew)
        ok = good & (w < -ew) & np.isfinite(depth)
        flo, fhi = _cap_box(p, n, rho, depth)
        at = rows[ok]
        lo[at] = np.maximum(lo[at], flo[ok])
        hi[at] = np.minimum(hi[at], fhi[ok])
        cuts.append((at,) + _cap_slab(p[ok], n[ok], depth[ok]))
    return lo, hi, cuts


def _face_sphere(pts, t, j):
    """Face j of simplices t (the face opposite vertex j, q): its circumcentre p, unit normal n
    towards q, circumradius rho (rounded up), h = (q - p).n, w = |q - p|^2 - rho^2 with a bound
    ew of its rounding, the face's size and whether it is far from flat."""
    d1 = t.shape[1]
    others = [k for k in range(d1) if k != j]
    q = pts[t[:, j]]
    a = pts[t[:, others[0]]]
    u = pts[t[:, others[1]]] - a
    if d1 == 3:
        p = a + 0.5 * u
        rho2 = 0.25 * np.einsum("mi,mi->m", u, u)
        n = np.stack([-u[:, 1], u[:, 0]], axis=1)
        span = np.sqrt(np.einsum("mi,mi->m", u, u))
        good = span > 0
    else:
        v = pts[t[:, others[2]]] - a
        uv = np.cross(u, v)
        uv2 = np.einsum("mi,mi->m", uv, uv)
        uu, vv = np.einsum("mi,mi->m", u, u), np.einsum("mi,mi->m", v, v)
        with _quiet():
            off = (uu[:, None] * np.cross(v, uv) + vv[:, None] * np.cross(uv, u)) \
                / (2.0 * uv2[:, None])
        p = a + off
        rho2 = np.einsum("mi,mi->m", off, off)
        n = uv
        span = np.sqrt(np.maximum(uu, vv))
        good = uv2 > 1e-16 * uu * vv  # a face far from flat: its circle is well defined
    with _quiet():
        n = n / np.sqrt(np.einsum("mi,mi->m", n, n))[:, None]
        qp = q - p
        h = np.einsum("mi,mi->m", qp, n)
        n = np.where((h < 0)[:, None], -n, n)
        h = np.abs(h)
        qq = np.einsum("mi,mi->m", qp, qp)
        w = qq - rho2
        ew = 1e-9 * (qq + rho2)  # far above the rounding of the terms
        rho = np.sqrt(rho2) * (1 + 1e-9) + 1e-9 * span
    return p, n, rho, h, w, ew, span, good & np.isfinite(w)


def _cap_box(foot, n, rim, depth):
    """The box round a cap: the disc of radius ``rim`` round ``foot`` in the plane of unit
    normal ``n``, swept by ``depth`` along n (a negative depth: against n)."""
    spread = rim[:, None] * np.sqrt(np.maximum(1.0 - n * n, 0.0))
    return (foot - spread + np.minimum(0.0, depth[:, None] * n),
            foot + spread + np.maximum(0.0, depth[:, None] * n))


def _cap_slab(foot, n, depth):
    """The slab a cap lies in, between its disc's plane and the plane ``depth`` along n:
    (n, a, b) with a <= n.x <= b, widened far beyond the rounding of n.foot.

    The box round a cap loses that the cap is thin: a tilted disc of a large rim (the flat
    simplices along the hull, whose hull face is nearly a line, have rims of tens of bounding
    boxes) spans its tilt times its rim across the plane, where the cap itself, inside the
    bounding box, stays within its depth of it. ``_clip_to_slab`` keeps that."""
    with _quiet():
        at = np.einsum("mi,mi->m", n, foot)
        pad = 1e-9 * (np.abs(foot).sum(axis=1) + np.abs(depth))
    return n, at + np.minimum(0.0, depth) - pad, at + np.maximum(0.0, depth) + pad


def _clip_to_slab(lo, hi, n, a, b):
    """The box round the part of each box (lo, hi) where a <= n.x <= b, rounded outwards: along
    axis k, x_k = t is reachable where n_k t plus the range of n.x over the box's other axes
    meets [a, b]. Boxes that are empty, unbounded or not finite, and axes along which n has no
    part, are left as they are."""
    with _quiet():
        plo, phi = n * lo, n * hi
        low, high = np.minimum(plo, phi), np.maximum(plo, phi)
        rest_lo = low.sum(axis=1)[:, None] - low
        rest_hi = high.sum(axis=1)[:, None] - high
        slack = 16.0 * _EPS * ((np.abs(plo) + np.abs(phi)).sum(axis=1) + np.abs(a) + np.abs(b))
        t1 = (a[:, None] - rest_hi - slack[:, None]) / n
        t2 = (b[:, None] - rest_lo + slack[:, None]) / n
    up = n > 0
    tlo, thi = np.where(up, t1, t2), np.where(up, t2, t1)
    use = ((n != 0) & np.isfinite(tlo) & np.isfinite(thi)
           & (np.isfinite(lo) & np.isfinite(hi) & (lo <= hi)).all(axis=1)[:, None]
           & np.isfinite(a)[:, None] & np.isfinite(b)[:, None])
    return np.where(use, np.maximum(lo, tlo), lo), np.where(use, np.minimum(hi, thi), hi)


def _far_caps(pts, t, planes):
    """For simplices whose circumcentre lies beyond one of their faces (far away for the flat
    simplices along the hull, where its computed place is too rough for the hull-plane cut),
    the hull-plane cut computed from that face: the centre is p + tau n (tau = w / 2h < 0, in
    the terms of ``_face_sphere``), r^2 = rho^2 + tau^2, and for a hull plane with unit normal
    m and offset o, at d = m.p + o and k = m.n, the centre lies h_m = d + tau k beyond it and
    r^2 - h_m^2 = rho^2 - d^2 - 2 d tau k + tau^2 |m x n|^2, every term accurate however large
    tau. The cap inside the plane furthest behind the centre has depth (r^2 - h_m^2) /
    (r + h_m), rim sqrt(r^2 - h_m^2), foot p - d m + tau (n - k m). Returns the boxes
    (lo, hi), unbounded where no cut applies, and the caps' slabs (``_cap_slab``)."""
    m, d1 = t.shape
    d = d1 - 1
    has = np.zeros(m, dtype=bool)
    p, n = np.zeros((m, d)), np.zeros((m, d))
    rho, tau, rel = np.zeros(m), np.zeros(m), np.zeros(m)
    for j in range(d1):
        pj, nj, rhoj, hj, wj, ewj, spanj, goodj = _face_sphere(pts, t, j)
        new = ~has & goodj & (wj < -ewj) & (hj > 1e-9 * spanj)
        with _quiet():
            tj = wj / (2.0 * hj)
        p = np.where(new[:, None], pj, p)
        n = np.where(new[:, None], -nj, n)  # tau > 0 along -n: the side away from q
        rho = np.where(new, rhoj, rho)
        tau = np.where(new, -tj, tau)
        with _quiet():  # tau's relative error, twice (tau^2), with room
            rel = np.where(new, 1e-8 + 2.0 * ewj / np.abs(wj) + 2e-9 * spanj / hj, rel)
        has |= new
    lo, hi = np.full((m, d), -np.inf), np.full((m, d), np.inf)
    rows = np.nonzero(has)[0]
    if len(rows) == 0 or len(planes) == 0:
        return lo, hi, []
    p, n, rho, tau, rel = p[rows], n[rows], rho[rows], tau[rows], rel[rows]
    normals, offsets = planes[:, :-1], planes[:, -1]
    best, _ = _furthest_plane(
        len(rows), planes,
        lambda i, j: p[i:j] @ normals.T + offsets + tau[i:j, None] * (n[i:j] @ normals.T))
    mn = normals[best]
    dd = np.einsum("mi,mi->m", mn, p) + offsets[best]
    k = np.einsum("mi,mi->m", mn, n)
    if d == 2:
        sin2 = (mn[:, 0] * n[:, 1] - mn[:, 1] * n[:, 0]) ** 2
    else:
        cr = np.cross(mn, n)
        sin2 = np.einsum("mi,mi->m", cr, cr)
    hm = dd + tau * k
    num = rho * rho - dd * dd - 2.0 * dd * tau * k + tau * tau * sin2
    terms = rho * rho + dd * dd + 2.0 * np.abs(dd * tau * k) + tau * tau * sin2
    # rounded up, so the cap only grows: tau's error, and sin2's own (a few eps) times tau^2
    num = num + rel * terms + 1e-15 * tau * tau + 1e-12 * (rho * rho)
    r = np.sqrt(rho * rho + tau * tau)
    ok = (hm > 0) & (num > 0) & np.isfinite(num)
    with _quiet():
        depth = num / (r + hm)
        rim = np.sqrt(num)
        foot = p - dd[:, None] * mn + tau[:, None] * (n - k[:, None] * mn)
    flo, fhi = _cap_box(foot, mn, rim, -depth)
    at = rows[ok]
    lo[at], hi[at] = flo[ok], fhi[ok]
    return lo, hi, [(at,) + _cap_slab(foot[ok], mn[ok], -depth[ok])]


def _cut(lo, hi, clo, chi, cuts):
    """Boxes (lo, hi) cut down to the caps' boxes (clo, chi) and to the caps' slabs (``cuts``:
    rows, n, a, b, from ``_cap_slab``)."""
    lo, hi = np.maximum(lo, clo), np.minimum(hi, chi)
    for at, n, a, b in cuts:
        if len(at):
            lo[at], hi[at] = _clip_to_slab(lo[at], hi[at], n, a, b)
    return lo, hi


def final_simplices(pts, s, region_lo, region_hi, box_lo, box_hi, planes, extras=(), nbs=None,
                    outside=None):
    """For simplices ``s`` of local points ``pts``: which are final.

    Points outside the region lie in the bounding box, inside every hull plane (``planes``,
    pushed outwards by a margin), and outside the extra boxes (strips) the block holds. A ball
    is final when it misses the bounding box beyond the region. Failing that, the box round its
    part in the bounding box, cut down where the centre lies beyond a hull face or plane to the
    box round the cap inside it (simplices along the hull have huge circumballs with a thin part
    inside) and to the part of that box in the cap's slab, must meet the bounding box beyond the
    region only inside the extra boxes, or (``outside`` given, an ``_Outside``) the ball's part
    in that box must meet only bins that hold no point outside the block."""
    scale = float(max(np.abs(box_lo).max(), np.abs(box_hi).max()))
    slabs = [(np.asarray(lo), np.asarray(hi)) for lo, hi in
             _slabs(region_lo, region_hi, box_lo, box_hi)]
    extras = [(np.asarray(lo), np.asarray(hi)) for lo, hi in extras]
    box_lo, box_hi = np.asarray(box_lo), np.asarray(box_hi)
    centre, radius, err = _circumcentres(pts, s)
    reach = radius + 2.0 * err + 64.0 * _EPS * (scale + np.abs(centre).max(axis=1) + radius)
    ok = _ball_misses(centre, reach, slabs)
    retry = np.nonzero(~ok & np.isfinite(reach))[0]
    if len(retry):
        c, r = centre[retry], reach[retry]
        lo, hi = _ball_in_box(c, r, box_lo, box_hi)
        pad = (1e-9 * scale + 64.0 * _EPS * (np.abs(c).max(axis=1) + r))[:, None]
        # First the caps over the simplices' own hull faces, which need no hull plane; then,
        # for the balls those leave uncovered (fewer), the caps along the hull planes, whose
        # work is balls times planes.
        if nbs is not None:
            lo, hi = _cut(lo, hi, *_face_caps(pts, s[retry], nbs[retry]))
        covered = _covered(lo - pad, hi + pad, slabs, extras)
        rest = np.nonzero(~covered)[0]
        if len(rest) and len(planes) and len(rest) * len(planes) <= _CAP_WORK:
            planes = np.asarray(planes)
            rlo, rhi = _cut(lo[rest], hi[rest], *_hull_cap(c[rest], r[rest], planes))
            rlo, rhi = _cut(rlo, rhi, *_far_caps(pts, s[retry[rest]], planes))
            lo[rest], hi[rest] = rlo, rhi
            covered[rest] = _covered(rlo - pad[rest], rhi + pad[rest], slabs, extras)
        lo, hi = lo - pad, hi + pad
        if outside is not None:
            rest = np.nonzero(~covered)[0]
            covered[rest] = ~outside.meets(c[rest], r[rest], lo[rest], hi[rest])
        ok[retry] = covered
    return ok


class _Outside:
    """Where the points a block does not hold may lie: the bins (a grid over the bounding box)
    that hold more of all the points than of the block's local points. Each point is counted in
    its bin by one C++ pass (``_core.cell_counts``), the same for all points and for the local
    ones, so a bin whose counts agree holds no outside point, and a ball that meets no other bin
    holds none either. It is what makes a ball final that reaches past the region into empty
    space (between clusters, inside a sphere of points)."""

    def __init__(self, bins: Grid, total: np.ndarray, local_pts: np.ndarray, threads=1):
        local = _core.cell_counts(np.ascontiguousarray(local_pts, dtype=np.float64),
                                  bins.lo.tolist(), bins.width.tolist(), bins.counts.tolist(),
                                  threads)
        self.marked = np.ascontiguousarray((total > local).ravel())
        self.any = bool(self.marked.any())
        self.bins = bins
        self.threads = threads
        scale = float(max(np.abs(bins.lo).max(), np.abs(bins.hi).max(), bins.width.max()))
        self.margin = 1e-9 * scale  # far above the rounding of a point's bin

    def meets(self, centre, reach, lo, hi):
        """Per ball (``centre``, ``reach``) cut to its box (rows of ``lo``, ``hi``): True where
        it meets a bin with an outside point (``_core.balls_in_bins``)."""
        if not self.any or len(centre) == 0:
            return np.zeros(len(centre), dtype=bool)
        b = self.bins
        r = _core.balls_in_bins(np.ascontiguousarray(centre, dtype=np.float64),
                                np.ascontiguousarray(reach, dtype=np.float64),
                                np.ascontiguousarray(lo, dtype=np.float64),
                                np.ascontiguousarray(hi, dtype=np.float64), b.lo.tolist(),
                                b.width.tolist(), b.counts.tolist(), self.marked, self.margin,
                                self.threads)
        return r.view(bool)


def _judge(dpts, s, nb, req, grid, cell, ghost, planes, extras, threads=1, outside=None,
           inside=None, why=None):
    """Whether simplices ``s[req]`` are all final (tested in pieces of ``_PIECE``, so that the
    temporaries stay small) against the region ``cell`` grown by ``ghost``.

    On the host, for GPU blocks too. The first test (the circumball with its rounding bound
    misses the bounding box beyond the region), which almost every simplex passes, runs in C++
    over all of them: ``inside`` (a byte per simplex) where the border pass gave it on the same
    balls, else ``_core.circumballs_inside_region`` (the same centre, bound and slabs as
    ``final_simplices``); only the others are tested here, in NumPy. Where one is not final and
    ``why`` is a list, a line saying which goes into it (the block's statistics carry it)."""
    clo, chi = cell
    rlo, rhi = clo - ghost, chi + ghost
    if len(req) and inside is not None:
        req = req[inside[req] == 0]
    elif len(req):
        scale = float(max(np.abs(grid.lo).max(), np.abs(grid.hi).max()))
        inside = _core.circumballs_inside_region(dpts, s, req, rlo.tolist(), rhi.tolist(),
                                                 grid.lo.tolist(), grid.hi.tolist(), scale,
                                                 threads)
        req = req[inside == 0]
    for i in range(0, len(req), _PIECE):
        ok = final_simplices(dpts, s[req[i:i + _PIECE]], rlo, rhi, grid.lo, grid.hi, planes,
                             extras, nb[req[i:i + _PIECE]], outside)
        if not bool(ok.all()):
            if why is not None:
                why.append(_why_not_final(dpts, s, nb, req[i:i + _PIECE], ok))
            return False
    return True


def _why_not_final(pts, s, nb, piece, ok):
    """A line on the balls of a piece that are not final: how many, and the first one's radius,
    centre and whether it has a face on the hull (the flat simplices along the hull do)."""
    bad = piece[~ok]
    c, r, _ = _circumcentres(pts, s[bad[:1]])
    hull = bool((nb[bad[0]] < 0).any())
    return (f"{len(bad)} of {len(piece)} tested balls in a piece not final; the first: radius "
            f"{r[0]:.3g}, centre {np.array2string(c[0], precision=4)}, "
            f"{'a' if hull else 'no'} face on the hull")


def _borders(pts, s, nb, own, block, grid, threads=1, region=None):
    """What block ``block`` sends the others for their second round (``_core.block_borders``):
    per target block, the local indices of its own points that the target's stars may use;
    with ``region`` (lo, hi) also the first finality test of its stars (``inside``), on the
    same balls."""
    scale = float(max(np.abs(grid.lo).max(), np.abs(grid.hi).max()))
    box = {} if region is None else dict(region_lo=region[0].tolist(),
                                         region_hi=region[1].tolist(),
                                         bounds_lo=grid.lo.tolist(), bounds_hi=grid.hi.tolist())
    return _core.block_borders(pts, s, nb, own, int(block), grid.lo.tolist(),
                               grid.width.tolist(), grid.counts.tolist(), 1e-9 * scale, scale,
                               threads=threads, **box)


def _not_done(block, ghost, nlocal, tested, borders, why=""):
    return dict(block=block, done=False, ghost=ghost, nlocal=nlocal, tested=tested,
                borders=borders, why=why)


def _local_points(parts, hull):
    """The local points: the block's parts from the pieces (points, global ids, owner blocks;
    each part's ids increasing, the pieces in increasing order of their ids, so no sort is
    needed) and the global hull's extreme points (the same, ids increasing) that are not among
    them, put in their places; copies read as the first. Returns (ids, points, owners).

    One copy of each part, by slices between the few places where a hull point goes in (the
    concatenation and the insertions cost three copies each: 1 s for a GPU block of 10^7 2D
    points)."""
    got = [p for p in parts if p is not None and len(p[1])]
    h_pts, h_ids, h_blk = hull
    d = h_pts.shape[1]
    # the hull points already there, and where the others go among the parts' points
    present = np.zeros(len(h_ids), dtype=bool)
    before = np.zeros(len(h_ids), dtype=np.int64)  # parts' points with lower ids
    for p in got:
        at = np.searchsorted(p[1], h_ids)
        present |= (at < len(p[1])) & (p[1][np.minimum(at, len(p[1]) - 1)] == h_ids)
        before += at
    new = np.nonzero(~present)[0]
    total = sum(len(p[1]) for p in got) + len(new)
    # (32-bit ids and blocks, as the output: fewer than 2^31 - 1 points)
    ids = np.empty(total, dtype=np.int32)
    pts = np.empty((total, d), dtype=np.float64)
    blk = np.empty(total, dtype=np.int32)
    slots = before[new] + np.arange(len(new))  # the new hull points' rows
    ids[slots], pts[slots], blk[slots] = h_ids[new], h_pts[new], h_blk[new]
    start = 0  # the first part point's place among the parts' points
    for p in got:
        m = len(p[1])
        # the new hull points that go in within this part: its points shift by one at each
        inside = np.nonzero((before[new] > start) & (before[new] < start + m))[0]
        shift0 = int(np.count_nonzero(before[new] <= start))
        edges = [0] + (before[new][inside] - start).tolist() + [m]
        for k in range(len(edges) - 1):
            a, b = edges[k], edges[k + 1]
            if a == b:
                continue
            row = start + a + shift0 + k
            ids[row:row + b - a] = p[1][a:b]
            pts[row:row + b - a] = p[0][a:b]
            blk[row:row + b - a] = p[2][a:b]
        start += m
    return ids, pts, blk


def _curve_order(ids, pts, blk, grid: Grid):
    """The local points along the Hilbert curve (``_core.hilbert_order``; points with equal
    coordinates keep their order, so a point's first copy is still its lowest id). In the order
    of their ids, a random input made every vertex that the passes over the simplices read (the
    borders, the output, the test) a cache miss: on one thread, 10^6 points in 2 blocks, the
    borders took 82 ms (2D) and 387 ms (3D), here 44 and 296, the whole call 3-5 % less
    (docs/performance.md); on a host whose cores were busy the output went from 1.31 s to 0.29.

    The passes take a simplex's *lowest local* vertex as its owner and as the matcher of its
    faces, so the owner is the vertex first on this curve (ties: the lowest id). Every block
    must order any two points alike, or a simplex between blocks would be output twice or not
    at all: the curve is laid over the points' bounding box, and every block's is the global
    one, since each holds the global hull's extreme points, which attain every bound (a face of
    the hull has a vertex). Checked here, a pass over the points: a block whose box differed
    would be a bug, never a wrong answer."""
    b = _core.point_bounds(pts)
    if len(pts) and not (np.array_equal(b["lo"], grid.lo) and np.array_equal(b["hi"], grid.hi)):
        raise RuntimeError("gpugeom.dask: a block's local points do not span the global bounding "
                           "box, so its curve order would differ from the others' (a bug: "
                           "please report it with the input)")
    order = _core.hilbert_order(pts)
    return ids[order], pts[order], blk[order]


def _emit(ids, pts, blk, s, nb, rows, threads=1):
    """The output of the owned simplices ``rows`` (every simplex whose lowest vertex is an own
    point): global ids, and per face the neighbour as a row here (-1: none) or -2 (another
    block's, found by the face: ``req_owner`` the block that matches it, ``req_key`` its sorted
    vertex ids, ``req_pos`` row * (d + 1) + face); the vertices used and their coordinates. In C++
    (``_core.block_output``) for a GPU block too: its output goes to the host anyway, and the
    gathers in CuPy and NumPy this replaced cost 2 s for a block of 10^7 points on an H200,
    where copying the simplices over costs a tenth of that. ``s``, ``nb``: on the host."""
    out = _core.block_output(s, nb, rows, ids, blk, pts, threads)
    out.pop("used")
    return out


def _done(block, ghost, nlocal, tested, out, copies):
    return dict(block=block, done=True, ghost=ghost, nlocal=nlocal, tested=tested,
                copies=copies, **out)


def _copies(ids, blk, block, tri):
    """Pairs (an own point, its earlier copy) in global ids."""
    dup = np.asarray(tri.duplicate_of).astype(np.int64)
    copy = np.nonzero((dup >= 0) & (blk == block))[0]
    return np.stack([ids[copy], ids[dup[copy]]], axis=1)


def _triangulated(pts, owned, backend, threads):
    """The local triangulation and what a round requires of it: the stars of the own points
    must be final. Returns (the Delaunay, its simplices and neighbours on the host, the owned
    simplices, the required mask). Only the triangulation runs where the block runs (its GPU
    where it has one); the simplices then come to the host, which the output needs anyway, and
    the rule, the finality test and the output are C++ passes on the host's threads. (On a GPU
    the test in CuPy and the passes on one host thread took 6 s of a block of 5·10^6 3D points
    whose triangulation took 0.5 s.) Raises DegenerateInputError as Delaunay does."""
    tri = Delaunay(np.asarray(pts), backend=backend, threads=threads)
    # on the host (the input was), as the triangulation gives them (int32: half the bytes of
    # int64 to copy from a GPU); the passes take either
    s, nb = np.asarray(tri.simplices), np.asarray(tri.neighbors)
    r = _core.block_required(s, nb, owned, threads)
    return tri, s, nb, r["owned_rows"], r["required"].view(bool)


def _held(hull, received):
    """The points a second round holds besides its own: the hull's extreme points and the
    borders the other blocks sent (points, ids, owner blocks), each point once, ids increasing."""
    got = [hull] + [r for r in received if r is not None and len(r[1])]
    ids = np.concatenate([g[1] for g in got])
    ids, at = np.unique(ids, return_index=True)
    return (np.concatenate([g[0] for g in got])[at], ids, np.concatenate([g[2] for g in got])[at])


def _border_parts(ids, pts, blk, b):
    """The borders of ``_core.block_borders`` as a dict: target block -> (points, ids, owner
    blocks)."""
    out = {}
    for k, t in enumerate(b["targets"].tolist()):
        v = b["vertices"][b["offsets"][k]:b["offsets"][k + 1]]
        out[t] = (pts[v], ids[v], blk[v])
    return out


def triangulate_block(block: int, grid: Grid, ghost: float, extras: dict, parts, hull, counts,
                      backend: str, threads: int, received=None) -> dict:
    """Triangulates block ``block``: in the first round (``received`` None) with ghost width
    ``ghost`` and the strips ``extras`` along the sides (a dict of boxes), and tests its stars;
    in the second with the borders the other blocks sent it (``received``: per block, (points,
    ids, owner blocks) or None), where its stars are final without a test.

    ``parts``: per input piece, (points, global ids, owner blocks) of its points the block
    owns or that lie in its region or strips (None where none); ``hull``: (points, ids,
    owner blocks, facet planes) of the global hull (its extreme points; the planes pushed
    outwards by a margin); ``counts``: (a Grid of bins, the count of all points per bin; None in
    the second round, which has no test). Returns
    a dict: ``done``; when done, ``simplices`` (global ids, the owned ones), ``nb_local`` (per
    face: an owned simplex's row here, -1 none, -2 another block's), the face requests for the
    others (``req_owner``, ``req_key``: sorted face ids, ``req_pos``: row * (d + 1) + face),
    ``copies`` (pairs: an own point, its earlier copy), ``vertices`` and ``vertex_points`` (the
    owned simplices' vertices, in the block's curve order, and their coordinates); after the
    first round,
    ``borders`` (target block -> (points, ids, owner blocks): what this block sends it)."""
    d = grid.ndim
    second = received is not None
    covers = grid.covers_all(block, ghost)
    if not any(p is not None and bool((p[2] == block).any()) for p in parts):
        z = np.zeros(0, np.int32)
        empty = dict(simplices=np.zeros((0, d + 1), np.int32),
                     nb_local=np.zeros((0, d + 1), np.int32), req_owner=z,
                     req_key=np.zeros((0, d), np.int32), req_pos=z, vertices=z,
                     vertex_points=np.zeros((0, d)), borders={})
        return _done(block, ghost, 0, 0, empty, np.zeros((0, 2), np.int32))
    ids, pts, blk = _curve_order(*_local_points(parts, _held(hull[:3], received) if second
                                                else hull[:3]), grid)
    own = blk == block
    try:
        tri, s, nb, mine, required = _triangulated(pts, own, backend, threads)
    except _core.DegenerateInputError:
        if covers or second:
            raise  # the hull's points are here: the whole set is degenerate, as a single run says
        # no triangulation to take a border from: every own point goes to every block
        mine_all = (pts[own], ids[own], blk[own])
        return _not_done(block, ghost, len(ids), 0,
                         {t: mine_all for t in range(grid.nblocks) if t != block})
    tested = 0
    bord = {}
    if not second:
        outside = None if covers else _Outside(counts[0], counts[1], pts, threads)
        test = outside is not None and outside.any  # (else every point is here: all is final)
        cell = grid.cell_box(block)
        b = _borders(pts, s, nb, own, block, grid, threads,
                     (cell[0] - ghost, cell[1] + ghost) if test else None)
        bord = _border_parts(ids, pts, blk, b)
        if test:
            req = np.nonzero(required)[0]
            tested = int(len(req))
            why = []
            if not _judge(pts, s, nb, req, grid, cell, ghost, hull[3], list(extras.values()),
                          threads, outside, b["inside"], why):
                return _not_done(block, ghost, len(ids), tested, bord, why[0] if why else "")
    out = _emit(ids, pts, blk, s, nb, mine, threads)
    return _done(block, ghost, len(ids), tested, dict(out, borders=bord),
                 _copies(ids, blk, block, tri))
