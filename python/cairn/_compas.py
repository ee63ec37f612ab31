"""Cairn's contact forces written back into COMPAS assembly data, as compas_cra
writes its own (cairn.compas_forces; docs/python.md, "COMPAS")."""

import copy

import numpy as np


def _unwrap(value):
    # COMPAS 2 {"dtype", "data"} and COMPAS 1 {"dtype", "value"} wrappers.
    while isinstance(value, dict) and "dtype" in value and ("data" in value or "value" in value):
        value = value["data"] if "data" in value else value["value"]
    return value


def _edges(doc):
    """The graph's edge dict {u: {v: attributes}} of an assembly's data."""
    root = _unwrap(doc)
    graph = _unwrap(root.get("graph", root)) if isinstance(root, dict) else None
    if not isinstance(graph, dict) or not isinstance(graph.get("edge"), dict):
        raise ValueError("compas_forces: not a COMPAS assembly (no graph edges found)")
    return graph["edge"]


def _interfaces(edges):
    """(u, v, interface data, its points (k, 3), unit xaxis, yaxis, normal u -> v)
    of every stored interface, in the file's order."""
    for u, by_v in edges.items():
        for v, attributes in by_v.items():
            for interface in (attributes or {}).get("interfaces") or []:
                data = _unwrap(interface)
                points = np.array([_unwrap(p) for p in data["points"]], dtype=float)
                frame = _unwrap(data["frame"])
                x = np.asarray(_unwrap(frame["xaxis"]), dtype=float)
                y = np.asarray(_unwrap(frame["yaxis"]), dtype=float)
                n = np.cross(x, y)
                yield (str(u), str(v), data, points, x / np.linalg.norm(x),
                       y / np.linalg.norm(y), n / np.linalg.norm(n))


def fill_forces(doc, r):
    doc = copy.deepcopy(doc)
    if r.get("dimension") != 3:
        raise ValueError("compas_forces: the result is not of a 3-D (COMPAS) assembly")
    contacts = r["contacts"]
    tol = float(r["tolerances"]["length"])
    # The force each contact puts on its part a: N n + f (n from b into a).
    on_a = [c["normal_force"] * np.asarray(c["normal"], dtype=float) +
            np.asarray(c["friction_force"], dtype=float) for c in contacts]
    points = np.array([c["point"] for c in contacts], dtype=float).reshape(-1, 3)
    normals = np.array([c["normal"] for c in contacts], dtype=float).reshape(-1, 3)
    used = np.zeros(len(contacts), dtype=bool)
    by_pair = {}
    for k, c in enumerate(contacts):
        by_pair.setdefault(frozenset(c["parts"]), []).append(k)

    found = 0
    for u, v, data, interface_points, x, y, n in _interfaces(_edges(doc)):
        found += 1
        forces = []
        candidates = by_pair.get(frozenset((u, v)), [])
        for p in interface_points:
            f_v = np.zeros(3)  # the force on v at p
            for k in candidates:
                if used[k] or np.linalg.norm(points[k] - p) > tol:
                    continue
                a = contacts[k]["parts"][0]
                # Cairn's normal is from b into a: -n when a is u, +n when a is v.
                if normals[k] @ (-n if a == u else n) < 1 - 1e-6:
                    continue
                used[k] = True
                f_v += -on_a[k] if a == u else on_a[k]
            along = float(f_v @ n)
            forces.append({"c_np": max(0.0, along), "c_nn": max(0.0, -along),
                           "c_u": float(f_v @ x), "c_v": float(f_v @ y)})
        data["forces"] = forces
    if found == 0:
        raise ValueError("compas_forces: the assembly data stores no interfaces "
                         "(compas_cra's assembly_interfaces_numpy finds them)")
    # A force Cairn found where no stored interface has a point would be lost.
    scale = max([abs(c["normal_force"]) for c in contacts] + [0.0])
    lost = [k for k in range(len(contacts))
            if not used[k] and contacts[k]["normal_force"] > 1e-9 * scale]
    if lost:
        c = contacts[lost[0]]
        raise ValueError(
            f"compas_forces: {len(lost)} contact(s) carrying force are at no point of a stored "
            f"interface (the first: parts {c['parts']}, point {c['point']}); check the model "
            "from_compas(..., interfaces='stored') to use the stored interfaces as the contacts")
    return doc
