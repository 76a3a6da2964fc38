#!/usr/bin/env python3
"""Independent check of `verify scene --vtk` output.

For every output directory given: reads `solution.pvd` with Python's own XML parser and every
`.vtu` it lists with meshio (a reader that shares no code with vtkio), and checks them against
the `solution.json` the same run wrote:

- the .pvd time values equal the JSON snapshot times, in order;
- each .vtu has the JSON's node coordinates (z = 0) and its triangles (or one line cell per
  element of an interval mesh);
- the expected arrays with their shapes: point data displacement and velocity (n, 3) (velocity
  absent exactly where the JSON snapshot has no `w`: t_0 of the quasistatic models), the contact
  arrays (n,), cell data strain and stress (c, 9) symmetric, von_mises (c,), body_id (c,) = 0,
  region (c,) integers ≥ 0;
- every value finite;
- values against the JSON: displacement and velocity at every node (dynamic: the velocity at
  the final time, the only one its JSON holds); for the quasistatic plane the
  in-plane stress, the strain recomputed here from the displacement (P1 gradients), von Mises
  recomputed here from the stress tensor (and equal to the JSON's plane-stress norm where
  σ_33 = 0), and the resultant of the nodal contact pressure (Σ_i m_i p_i with m_i half the
  lengths of the adjacent contact edges) against the JSON's contact force at that time; for the
  rod the contact pressure at x = L against −σ(L, t_n); for a dynamic plane body the strain and
  stress tensors (σ_33 included) against the law (linear, St Venant–Kirchhoff, neo-Hooke with
  the λ, μ of the JSON's description: the body's, then each region's) of each cell's `region`,
  written here from F = I + ∇u;
- the `region` map against the Gmsh file itself, when the JSON names its scene (`source`, a
  dynamic scene) and the scene has `[[region]]`: the scene's .msh read with meshio, each
  region's triangles (its physical group, placed by x ↦ scale x + offset) found among the cells
  by their centroids must carry the region's index + 1, every other cell 0.

For a multibody scene (the JSON lists `bodies`): one grid of all bodies, each body's nodes after
the previous bodies'; the points and triangles against the JSON's bodies; `body_id` per cell
the body's index; displacement and velocity at every node against the JSON snapshot's bodies;
the contact arrays (`contact_node`, `contact_pressure`, `contact_gap`, `contact_slip`,
`contact_active`, and `friction_traction` where a pair has friction) present exactly when the
scene has pairs, `contact_node` 1 exactly on the pairs' slave nodes, the pressure Σ λ_N / w, the
active flag and the candidates' gap and slip against the snapshot's contact states, every
contact array zero off the contact boundary; strain and stress against each body's law written
here (its description), von Mises from the stress tensor.

Usage: check_vtk.py DIR [DIR ...]; exits 1 on the first failed directory's list of problems.
"""

import json
import math
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np

CONTACT_QUASISTATIC = ["contact_pressure", "contact_normal_velocity", "contact_active", "contact_node"]
CONTACT_DYNAMIC = ["contact_pressure", "contact_gap", "contact_active", "contact_node"]
FRICTION = ["friction_traction", "slip_velocity"]
CONTACT_MULTIBODY = ["contact_node", "contact_pressure", "contact_gap", "contact_slip", "contact_active"]
CELL = ["strain", "stress", "von_mises", "body_id", "region"]
LAW = r"(linear elastic|St Venant-Kirchhoff|neo-Hooke), plane strain \(λ = ([^,]+), μ = ([^)]+)\)"


class Problems(list):
    def check(self, ok, message):
        if not ok:
            self.append(message)
        return ok


def close(a, b, rel=1e-12):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = max(1.0, float(np.max(np.abs(b))) if b.size else 1.0)
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= rel * scale))


def von_mises(t):
    """σ_vM of row-major 3 × 3 tensors (c, 9)."""
    s11, s22, s33, s12 = t[:, 0], t[:, 4], t[:, 8], t[:, 1]
    return np.sqrt(0.5 * ((s11 - s22) ** 2 + (s22 - s33) ** 2 + (s33 - s11) ** 2) + 3 * s12**2)


def p1_strain(nodes, triangles, u):
    """ε(u) of P1 triangles, (c, 3) as (11, 22, 12), computed here from the node coordinates."""
    out = np.zeros((len(triangles), 3))
    for e, (a, b, c) in enumerate(triangles):
        (x0, y0), (x1, y1), (x2, y2) = nodes[a], nodes[b], nodes[c]
        det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        g = np.array([[y1 - y2, x2 - x1], [y2 - y0, x0 - x2], [y0 - y1, x1 - x0]]) / det
        ux = np.array([u[2 * a], u[2 * b], u[2 * c]])
        uy = np.array([u[2 * a + 1], u[2 * b + 1], u[2 * c + 1]])
        out[e] = [g[:, 0] @ ux, g[:, 1] @ uy, 0.5 * (g[:, 1] @ ux + g[:, 0] @ uy)]
    return out


def law_stress(body, F, material=0):
    """The stress and strain (c, 9) of a plane-strain hyperelastic law written here from its
    definition, for deformation gradients F (c, 2, 2) (F_33 = 1), or None when `body` (the JSON's
    description) names no law known here; `material` 0 is the body's law, r + 1 region r's (the
    laws in the order the description lists them). Small strain: ε = sym(F − I), σ = λ tr ε I + 2μ ε,
    σ_33 = λ tr ε; St Venant–Kirchhoff: E = ½(FᵀF − I), S = λ tr E I + 2μ E, σ = F S Fᵀ / J,
    σ_33 = λ tr E / J; neo-Hooke: σ = (μ (F Fᵀ − I) + λ ln J I) / J, σ_33 = λ ln J / J."""
    import re
    laws = list(re.finditer(LAW, body))
    if material >= len(laws):
        return None
    m = laws[material]
    law, lam, mu = m.group(1), float(m.group(2)), float(m.group(3))
    eye = np.eye(2)
    J = np.linalg.det(F)
    Ft = np.transpose(F, (0, 2, 1))
    if law == "linear elastic":
        strain = 0.5 * (F + Ft) - eye
        tr = np.trace(strain, axis1=1, axis2=2)
        sigma = lam * tr[:, None, None] * eye + 2 * mu * strain
        s33 = lam * tr
    elif law == "St Venant-Kirchhoff":
        strain = 0.5 * (Ft @ F - eye)
        tr = np.trace(strain, axis1=1, axis2=2)
        S = lam * tr[:, None, None] * eye + 2 * mu * strain
        sigma = F @ S @ Ft / J[:, None, None]
        s33 = lam * tr / J
    else:
        strain = 0.5 * (Ft @ F - eye)
        lnJ = np.log(J)
        sigma = (mu * (F @ Ft - eye) + lam * lnJ[:, None, None] * eye) / J[:, None, None]
        s33 = lam * lnJ / J

    def full(t, t33):
        out = np.zeros((len(t), 9))
        out[:, [0, 1, 3, 4]] = t.reshape(-1, 4)
        out[:, 8] = t33
        return out

    return full(sigma, s33), full(strain, np.zeros(len(strain)))


def deformation_gradients(nodes, triangles, u):
    """F = I + ∇u of P1 triangles, (c, 2, 2), computed here from the node coordinates."""
    F = np.zeros((len(triangles), 2, 2))
    for e, (a, b, c) in enumerate(triangles):
        (x0, y0), (x1, y1), (x2, y2) = nodes[a], nodes[b], nodes[c]
        det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        g = np.array([[y1 - y2, x2 - x1], [y2 - y0, x0 - x2], [y0 - y1, x1 - x0]]) / det
        U = np.array([u[a], u[b], u[c]])  # (3 nodes, 2 components)
        F[e] = np.eye(2) + U.T @ g
    return F


def contact_masses(nodes, triangles, on_contact):
    """m_i = half the lengths of the boundary edges whose two ends are contact nodes."""
    count = {}
    for t in triangles:
        for i in range(3):
            e = tuple(sorted((t[i], t[(i + 1) % 3])))
            count[e] = count.get(e, 0) + 1
    m = np.zeros(len(nodes))
    for (a, b), k in count.items():
        if k == 1 and on_contact[a] and on_contact[b]:
            length = math.dist(nodes[a], nodes[b])
            m[a] += 0.5 * length
            m[b] += 0.5 * length
    return m


def expected_regions(sol, triangles_xy):
    """The region of each cell (index + 1, 0 for the body's material) from the scene's Gmsh file
    read with meshio, or None when the JSON names no scene with [[region]]. `triangles_xy` (c, 3, 2)
    are the cells' vertices."""
    import tomllib
    source = Path(sol.get("source", ""))
    if not source.is_file():
        return None
    scene = tomllib.loads(source.read_text())
    regions = scene.get("region", [])
    body = scene.get("body") or scene.get("geometry") or {}
    if not regions or body.get("shape") != "gmsh":
        return None
    msh = meshio.read(source.parent / body["file"])
    scale, offset = body.get("scale", 1.0), np.array(body.get("offset", [0.0, 0.0]))
    tri = msh.cells_dict["triangle"]
    pts = msh.points[:, :2] * scale + offset
    key = lambda c: tuple(np.round(c / (scale * 1e-9)).astype(np.int64))
    cell_of = {key(c): e for e, c in enumerate(triangles_xy.mean(axis=1))}
    out = np.zeros(len(triangles_xy), int)
    for r, region in enumerate(regions):
        for t in msh.cell_sets_dict[region["group"]]["triangle"]:
            out[cell_of[key(pts[tri[t]].mean(axis=0))]] = r + 1
    return out


def family(sol):
    if "bodies" in sol:
        return "multibody"
    if "dimension" in sol:
        return "dynamic_" + sol["dimension"]
    if "triangles" in sol:
        return "plane"
    return "rod"


def snapshot_view(fam, sol, s):
    """(time, nodal displacement as (n, 2), nodal velocity (n, 2) or None) of a JSON snapshot."""
    n = len(sol["nodes"])
    if fam == "plane":
        w = s.get("w")
        return s["t"], np.reshape(s["u"], (n, 2)), None if w is None else np.reshape(w, (n, 2))
    if fam == "rod":
        pad = lambda v: np.column_stack([v, np.zeros(n)])
        w = s.get("w")
        return s["t"], pad(s["u"]), None if w is None else pad(w)
    if fam == "dynamic_plane":
        return s["time"], np.reshape(s["displacement"], (n, 2)), None
    return s["time"], np.column_stack([s["displacement"], np.zeros(n)]), None


def check_multibody(d: Path, sol, p: Problems):
    """The checks of a multibody series (module docs); returns (.vtu count, arrays seen)."""
    root = ET.parse(d / "solution.pvd").getroot()
    p.check(root.get("type") == "Collection", "the .pvd is not a Collection")
    entries = [(float(e.get("timestep")), e.get("file")) for e in root.iter("DataSet")]
    snaps = sol["snapshots"]
    p.check(len(entries) == len(snaps), f"{len(entries)} .vtu in the .pvd, {len(snaps)} JSON snapshots")
    bodies = sol["bodies"]
    offsets = np.cumsum([0] + [len(b["nodes"]) for b in bodies])
    nodes = np.concatenate([np.array(b["nodes"], float) for b in bodies])
    triangles = np.concatenate([np.array(b["triangles"], int) + o for b, o in zip(bodies, offsets)])
    body_of_cell = np.concatenate([np.full(len(b["triangles"]), i) for i, b in enumerate(bodies)])
    n, c = len(nodes), len(triangles)
    pairs = sol["pairs"]
    slave = np.zeros(n, bool)
    for pr in pairs:
        b = [x["name"] for x in bodies].index(pr["slave"])
        slave[offsets[b] + np.array(pr["slave_nodes"], int)] = True
    friction = any(pr["friction"] > 0 for pr in pairs)
    arrays_seen = set()
    for (t, file), s in zip(entries, snaps):
        where = f"{d.name}/{file} (t = {t})"
        p.check(t == s["time"], f"{where}: .pvd time {t!r}, JSON snapshot time {s['time']!r}")
        m = meshio.read(d / file)
        p.check(m.points.shape == (n, 3), f"{where}: points {m.points.shape}, JSON {n} nodes")
        if m.points.shape != (n, 3):
            continue
        p.check(close(m.points[:, :2], nodes, 0) and not np.any(m.points[:, 2]), f"{where}: coordinates differ from the JSON's bodies")
        kinds = [cb.type for cb in m.cells]
        p.check(kinds == ["triangle"], f"{where}: cell blocks {kinds}, expected [triangle]")
        conn = m.cells[0].data if m.cells else np.zeros((0, 3), int)
        p.check(np.array_equal(conn, triangles), f"{where}: triangles differ from the JSON's bodies'")
        pd = {k: np.asarray(v) for k, v in m.point_data.items()}
        cd = {k: np.asarray(v[0]) for k, v in m.cell_data.items()}
        arrays_seen |= set(pd) | set(cd)
        for name, a in list(pd.items()) + list(cd.items()):
            if np.issubdtype(a.dtype, np.floating):
                p.check(bool(np.all(np.isfinite(a))), f"{where}: `{name}` has non-finite values")
        u = np.concatenate([np.reshape(b["displacement"], (-1, 2)) for b in s["bodies"]])
        v = np.concatenate([np.reshape(b["velocity"], (-1, 2)) for b in s["bodies"]])
        for name, want in [("displacement", u), ("velocity", v)]:
            if p.check(name in pd and pd[name].shape == (n, 3), f"{where}: no `{name}` of shape ({n}, 3)"):
                p.check(close(pd[name][:, :2], want, 0) and not np.any(pd[name][:, 2]), f"{where}: {name} differs from the JSON's")
        # contact arrays
        want = CONTACT_MULTIBODY + (["friction_traction"] if friction else []) if pairs else []
        present = [k for k in CONTACT_MULTIBODY + ["friction_traction"] if k in pd]
        p.check(present == want, f"{where}: contact arrays {present}, expected {want}")
        for k in present:
            pd[k] = pd[k].reshape(-1)
        if present == want and pairs:
            p.check(np.array_equal(pd["contact_node"] == 1, slave) and np.all(np.isin(pd["contact_node"], [0, 1])),
                    f"{where}: contact_node is not 1 exactly on the pairs' slave nodes")
            for k in present:
                p.check(not np.any(pd[k][~slave]), f"{where}: `{k}` nonzero off the contact boundary")
            pressure, active = np.zeros(n), np.zeros(n)
            gap = np.full(n, np.inf)
            slip = np.zeros(n)
            for ct in s["contacts"]:
                i = offsets[ct["body"]] + ct["node"]
                pressure[i] += ct["pressure"]
                if ct["gap"] < gap[i]:
                    gap[i], slip[i] = ct["gap"], ct["slip"]
                active[i] = max(active[i], 1.0 if ct["active"] else 0.0)
            cand = np.isfinite(gap)
            p.check(close(pd["contact_pressure"], pressure, 1e-12), f"{where}: contact_pressure differs from Σ λ_N / w of the JSON's contact states")
            p.check(np.array_equal(pd["contact_active"], active), f"{where}: contact_active differs from the JSON's contact states")
            p.check(close(pd["contact_gap"][cand], gap[cand], 0) and close(pd["contact_slip"][cand], slip[cand], 0),
                    f"{where}: the candidates' gap or slip differ from the JSON's contact states")
        # cell data
        for name in ["strain", "stress", "von_mises", "body_id"]:
            p.check(name in cd, f"{where}: no cell array `{name}`")
        if not all(name in cd for name in ["strain", "stress", "von_mises", "body_id"]):
            continue
        p.check(np.array_equal(cd["body_id"].reshape(-1), body_of_cell), f"{where}: body_id is not each cell's body index")
        vm = cd["von_mises"].reshape(-1)
        p.check(close(vm, von_mises(cd["stress"]), 1e-12), f"{where}: von_mises differs from the stress tensor's")
        F = deformation_gradients(nodes, triangles, u)
        stress, strain = np.zeros((c, 9)), np.zeros((c, 9))
        for b, body in enumerate(bodies):
            law = law_stress(body["description"], F)
            if not p.check(law is not None, f"{where}: no law known here in {body['description']!r}"):
                continue
            on = body_of_cell == b
            stress[on], strain[on] = law[0][on], law[1][on]
        scale = max(1.0, float(np.max(np.abs(stress))))
        p.check(bool(np.all(np.abs(cd["stress"] - stress) <= 1e-9 * scale)),
                f"{where}: stress differs from the laws' written here (max {np.max(np.abs(cd['stress'] - stress))!r})")
        p.check(close(cd["strain"], strain, 1e-9), f"{where}: strain differs from the laws' measures written here")
    return len(entries), sorted(arrays_seen)


def check_dir(d: Path):
    p = Problems()
    sol = json.loads((d / "solution.json").read_text())
    fam = family(sol)
    if fam == "multibody":
        count, arrays = check_multibody(d, sol, p)
        return p, fam, count, arrays
    root = ET.parse(d / "solution.pvd").getroot()
    p.check(root.get("type") == "Collection", "the .pvd is not a Collection")
    entries = [(float(e.get("timestep")), e.get("file")) for e in root.iter("DataSet")]
    snaps = sol["snapshots"]
    p.check(len(entries) == len(snaps), f"{len(entries)} .vtu in the .pvd, {len(snaps)} JSON snapshots")
    if fam == "plane":
        nodes = np.array(sol["nodes"], float)
        triangles = np.array(sol["triangles"], int)
    elif fam == "dynamic_plane":
        nodes = np.array(sol["nodes"], float)
        triangles = np.array(sol["triangles"], int)
    else:
        x = np.array(sol["nodes"], float).reshape(-1)
        nodes = np.column_stack([x, np.zeros(len(x))])
        triangles = None
    n = len(nodes)
    cells_expected = len(triangles) if triangles is not None else n - 1
    arrays_seen = set()
    for k, ((t, file), s) in enumerate(zip(entries, snaps)):
        where = f"{d.name}/{file} (t = {t})"
        t_json, u_json, w_json = snapshot_view(fam, sol, s)
        p.check(t == t_json, f"{where}: .pvd time {t!r}, JSON snapshot time {t_json!r}")
        m = meshio.read(d / file)
        p.check(m.points.shape == (n, 3), f"{where}: points {m.points.shape}, JSON {n} nodes")
        p.check(close(m.points[:, :2], nodes, 0) and not np.any(m.points[:, 2]), f"{where}: coordinates differ from the JSON's")
        kinds = [c.type for c in m.cells]
        want = "triangle" if triangles is not None else "line"
        p.check(kinds == [want], f"{where}: cell blocks {kinds}, expected [{want}]")
        conn = m.cells[0].data if m.cells else np.zeros((0, 0))
        p.check(len(conn) == cells_expected, f"{where}: {len(conn)} cells, JSON {cells_expected}")
        if triangles is not None and len(conn) == len(triangles):
            p.check(np.array_equal(conn, triangles), f"{where}: triangles differ from the JSON's")
        pd = {k: np.asarray(v) for k, v in m.point_data.items()}
        cd = {k: np.asarray(v[0]) for k, v in m.cell_data.items()}
        arrays_seen |= set(pd) | set(cd)
        for name, a in list(pd.items()) + list(cd.items()):
            if np.issubdtype(a.dtype, np.floating):
                p.check(bool(np.all(np.isfinite(a))), f"{where}: `{name}` has non-finite values")
        # point data
        for name in ["displacement", "velocity"]:
            if name in pd:
                p.check(pd[name].shape == (n, 3), f"{where}: `{name}` shape {pd[name].shape}, expected ({n}, 3)")
        if not p.check("displacement" in pd, f"{where}: no `displacement`"):
            continue
        p.check(close(pd["displacement"][:, :2], u_json, 0) and not np.any(pd["displacement"][:, 2]),
                f"{where}: displacement differs from the JSON's")
        if fam in ("plane", "rod"):
            p.check(("velocity" in pd) == (w_json is not None), f"{where}: `velocity` present iff the JSON has w")
            if w_json is not None and "velocity" in pd:
                p.check(close(pd["velocity"][:, :2], w_json, 0), f"{where}: velocity differs from the JSON's w")
            contact = CONTACT_QUASISTATIC
        else:
            p.check("velocity" in pd, f"{where}: no `velocity`")
            contact = CONTACT_DYNAMIC
            # the JSON holds the velocity of the last state only
            if "velocity" in pd and t == sol["final_time"]:
                v = np.array(sol["final_velocity_nodal"], float).reshape(n, -1)
                p.check(close(pd["velocity"][:, : v.shape[1]], v, 0), f"{where}: velocity differs from the JSON's final velocity")
        present = [c for c in contact if c in pd]
        p.check(present in ([], contact), f"{where}: contact arrays {present}, expected all of {contact} or none")
        friction = [c for c in FRICTION if c in pd]
        p.check(friction in ([], FRICTION), f"{where}: friction arrays {friction}, expected both or none")
        for c in present + friction:
            a = pd[c].reshape(-1) if pd[c].ndim == 2 and pd[c].shape[1] == 1 else pd[c]
            p.check(a.shape == (n,), f"{where}: `{c}` shape {pd[c].shape}, expected ({n},)")
            pd[c] = a
        if present:
            on = pd["contact_node"] == 1
            p.check(bool(np.all((pd["contact_node"] == 0) | on)) and on.any(), f"{where}: contact_node is not a 0/1 flag with a contact node")
            for c in present + friction:
                p.check(not np.any(pd[c][~on]), f"{where}: `{c}` nonzero off the contact boundary")
            p.check(bool(np.all(np.isin(pd["contact_active"], [0.0, 1.0]))), f"{where}: contact_active is not 0/1")
        # cell data
        for name in CELL:
            p.check(name in cd, f"{where}: no cell array `{name}`")
        if not all(name in cd for name in CELL):
            continue
        for name in ["strain", "stress"]:
            a = cd[name]
            if p.check(a.shape == (cells_expected, 9), f"{where}: `{name}` shape {a.shape}"):
                p.check(close(a[:, 1], a[:, 3], 0) and not np.any(a[:, [2, 5, 6, 7]]), f"{where}: `{name}` is not a plane symmetric tensor")
        vm = cd["von_mises"].reshape(-1)
        bid = cd["body_id"].reshape(-1)
        region = cd["region"].reshape(-1)
        p.check(region.shape == (cells_expected,) and np.issubdtype(region.dtype, np.integer) and not np.any(region < 0),
                f"{where}: region is not a non-negative integer per cell")
        if region.shape == (cells_expected,) and triangles is not None and fam == "dynamic_plane":
            want = expected_regions(sol, nodes[triangles])
            if want is None:
                want = np.zeros(cells_expected, int)
            p.check(np.array_equal(region, want), f"{where}: region differs from the Gmsh file's groups ({int(np.sum(region != want))} cells)")
        p.check(vm.shape == (cells_expected,), f"{where}: von_mises shape {cd['von_mises'].shape}")
        p.check(bid.shape == (cells_expected,) and not np.any(bid), f"{where}: body_id is not 0 on every cell")
        if cd["stress"].shape == (cells_expected, 9) and vm.shape == (cells_expected,):
            p.check(close(vm, von_mises(cd["stress"]), 1e-12), f"{where}: von_mises differs from the stress tensor's")
        # family-specific cross-checks against the JSON
        if fam == "plane":
            st = np.array(s["stress"], float)
            p.check(close(cd["stress"][:, [0, 4, 1]], st, 0), f"{where}: stress differs from the JSON's")
            if not np.any(cd["stress"][:, 8]):
                p.check(close(vm, s["von_mises"], 1e-12), f"{where}: von_mises differs from the JSON's plane-stress norm")
            eps = p1_strain(nodes, triangles, np.array(s["u"], float))
            p.check(close(cd["strain"][:, [0, 4, 1]], eps, 1e-10), f"{where}: strain differs from the P1 strain of the displacement")
            if present:
                mass = contact_masses(nodes, triangles, pd["contact_node"] == 1)
                resultant = float(mass @ pd["contact_pressure"])
                i = sol["times"].index(t) if t in sol["times"] else None
                if p.check(i is not None, f"{where}: t not among the JSON's times"):
                    f = sol["contact_force"][i]
                    p.check(abs(resultant - f) <= 1e-10 * max(1.0, abs(f)),
                            f"{where}: Σ m_i p_i = {resultant!r}, JSON contact force {f!r}")
        if fam == "dynamic_plane":
            F = deformation_gradients(nodes, triangles, u_json)
            stress, strain = np.zeros((cells_expected, 9)), np.zeros((cells_expected, 9))
            known = True
            for mat in np.unique(region):
                law = law_stress(sol["body"], F, int(mat))
                if not p.check(law is not None, f"{where}: no law {mat} known here in {sol['body']!r}"):
                    known = False
                    continue
                on = region == mat
                stress[on], strain[on] = law[0][on], law[1][on]
            if known:
                scale = max(1.0, float(np.max(np.abs(stress))))
                p.check(bool(np.all(np.abs(cd["stress"] - stress) <= 1e-9 * scale)),
                        f"{where}: stress differs from the law's written here (max {np.max(np.abs(cd['stress'] - stress))!r})")
                p.check(close(cd["strain"], strain, 1e-9), f"{where}: strain differs from the law's measure written here")
        if fam == "rod" and present:
            sigma = sol["contact_stress"][s["n"]]
            p.check(pd["contact_pressure"][-1] == -sigma, f"{where}: contact pressure at L {pd['contact_pressure'][-1]!r}, JSON −σ(L) {-sigma!r}")
    return p, fam, len(entries), sorted(arrays_seen)


def main(dirs):
    failed = 0
    for d in map(Path, dirs):
        try:
            problems, fam, count, arrays = check_dir(d)
        except Exception as e:  # a file that cannot be read is a failure of the run
            problems, fam, count, arrays = Problems([f"{d}: {type(e).__name__}: {e}"]), "?", 0, []
        if problems:
            failed += 1
            print(f"FAIL {d.name} ({fam}): {len(problems)} problem(s)")
            for m in problems[:20]:
                print(f"    {m}")
        else:
            print(f"ok   {d.name} ({fam}): {count} .vtu; arrays {', '.join(arrays)}")
    print(f"{len(dirs) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1:]))
