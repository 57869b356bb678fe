"""septa.CutCells as a full result: faces with their holes, cells as oriented
face lists, volumes, supports; saved and converted (.vtu, .obj, pyvista,
meshio, the viewer) without losing a cell, a face or a bit of a coordinate."""
import json
from collections import Counter

import numpy as np
import pytest

import septa

pv = pytest.importorskip("pyvista")
meshio = pytest.importorskip("meshio")


def _box(lo, hi, outward=True):
    """The 12 triangles of an axis box (outward, or inward for a cavity)."""
    v = np.array([[x, y, z] for x in (lo, hi) for y in (lo, hi) for z in (lo, hi)], float)
    quads = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    t = np.array([[q[0], q[1], q[2]] for q in quads] + [[q[0], q[2], q[3]] for q in quads])
    return v, (t if outward else t[:, ::-1])


def hollow_cube():
    """[0,4]^3 with the cavity [1,3]^3: a plane at z = 2 cuts an annulus."""
    v0, t0 = _box(0.0, 4.0)
    v1, t1 = _box(1.0, 3.0, outward=False)
    return np.vstack([v0, v1]), np.vstack([t0, t1 + 8]), 64.0 - 8.0


def sphere():
    s = pv.Icosphere(radius=1.0, nsub=2)
    return np.asarray(s.points, float), s.faces.reshape(-1, 4)[:, 1:].astype(np.int64), s.volume


def random_planes(n, seed):
    rng = np.random.default_rng(seed)
    normals = rng.normal(size=(n, 3))
    points = rng.uniform(-0.6, 0.6, size=(n, 3))
    return np.hstack([normals, -(normals * points).sum(axis=1, keepdims=True)])


@pytest.fixture(params=["hollow", "sphere"])
def case(request):
    if request.param == "hollow":
        v, t, vol = hollow_cube()
        planes = [[0, 0, 1, -2], [1, 0, 0, -0.5]]
    else:
        v, t, vol = sphere()
        planes = random_planes(7, 11)
    return septa.cut_mesh(v, t, planes), vol, t


def _closed(polys):
    """Each directed edge of a cell's outward polygons is matched by its reverse."""
    edges = Counter()
    for p in polys:
        p = p.tolist()
        for a, b in zip(p, p[1:] + p[:1]):
            edges[(a, b)] += 1
    return all(edges[(b, a)] == n for (a, b), n in edges.items())


def test_counts_faces_cells_and_volumes(case):
    cut, volume, tris = case
    s = cut.summary()
    assert len(cut.cells) == len(cut.cell_volumes) == s["cut_cells"]
    assert len(cut.faces) == len(cut.face_cells) == s["cut_faces"]
    assert cut.cut_vertices == s["cut_vertices"] <= len(cut.points)
    assert s["embedding"]["report"]["intersecting_pairs"] == 0
    assert np.all(cut.cell_volumes > 0)
    assert abs(cut.cell_volumes.sum() - volume) <= 1e-12 * volume
    on_plane = cut.face_plane >= 0
    assert np.all(on_plane != (cut.face_triangle >= 0))  # exactly one support
    assert cut.face_triangle.max() < len(tris) and cut.face_plane.max() < len(cut.planes)
    # an interior (plane) face bounds exactly two distinct cells, a face of
    # the input surface exactly one, seen from its inside
    fc = cut.face_cells
    assert np.all(fc[on_plane] >= 0) and np.all(fc[on_plane, 0] != fc[on_plane, 1])
    assert np.all(fc[~on_plane, 0] >= 0) and np.all(fc[~on_plane, 1] == -1)
    # cells list each face with the orientation face_cells says
    seen = Counter()
    for c, faces in enumerate(cut.cells):
        for f, sgn in faces:
            assert fc[f, 0 if sgn > 0 else 1] == c
            seen[f] += 1
    assert all(seen[f] == 1 + int(on_plane[f]) for f in range(len(cut.faces)))
    # each cell's written outward polygons close up, and their divergence
    # theorem volume is the cell's volume
    for c, polys in enumerate(cut.cell_polygons()):
        assert _closed(polys), c
        vol = 0.0
        for p in polys:
            x = cut.points[p]
            vol += sum(np.dot(x[0], np.cross(x[i], x[i + 1])) for i in range(1, len(p) - 1)) / 6
        assert abs(vol - cut.cell_volumes[c]) <= 1e-12 * volume, c
    # loops: the outer one runs counter-clockwise about the support normal
    for f, loops in enumerate(cut.faces):
        n = cut.planes[cut.face_plane[f], :3] if on_plane[f] else None
        if n is not None:
            x = cut.points[loops[0]]
            area = sum(np.cross(x[i], x[(i + 1) % len(x)]) for i in range(len(x)))
            assert np.dot(area, n) > 0, f


def test_holes_are_kept():
    v, t, _ = hollow_cube()
    cut = septa.cut_mesh(v, t, [[0, 0, 1, -2]])
    assert cut.summary()["cut_cells"] == 2
    annuli = [f for f, loops in enumerate(cut.faces) if len(loops) > 1]
    assert len(annuli) == 1 and cut.face_plane[annuli[0]] == 0
    outer, hole = cut.faces[annuli[0]]
    # 8 points each: the vertical box edges and the side triangles' diagonals
    assert len(outer) == 8 and len(hole) == 8
    assert np.all(np.abs(cut.points[outer][:, :2] - 2).max(axis=1) == 2.0)
    assert np.all(np.abs(cut.points[hole][:, :2] - 2).max(axis=1) == 1.0)
    assert np.all(cut.points[np.concatenate([outer, hole]), 2] == 2.0)
    # written as triangles (a polyhedron face has one loop): an annulus of
    # 8 + 8 points needs 16
    assert len(cut.face_polygons[annuli[0]]) == 16


def test_vtu_round_trip(case, tmp_path):
    cut, volume, _ = case
    path = cut.save(tmp_path / "cells.vtu")
    g = pv.read(path)
    assert g.n_cells == len(cut.cells)
    assert set(np.unique(g.celltypes)) == {pv.CellType.POLYHEDRON}
    assert np.array_equal(np.asarray(g.points), cut.points)  # the same doubles
    # rows as meshio groups them (by point count, as `to_meshio`); cell_id names the cell
    ids = np.asarray(g.cell_data["cell_id"])
    assert np.array_equal(ids, np.concatenate(cut.to_meshio().cell_data["cell_id"]))
    assert np.array_equal(np.asarray(g.cell_data["volume"]), cut.cell_volumes[ids])
    for i in range(g.n_cells):
        surf = g.extract_cells([i]).extract_surface(algorithm="dataset_surface").triangulate()
        assert surf.n_open_edges == 0, i
        assert abs(surf.volume - cut.cell_volumes[ids[i]]) <= 1e-9 * volume, i


def test_pyvista_and_meshio_round_trips(case, tmp_path):
    cut, volume, _ = case
    g = cut.to_pyvista()
    assert g.n_cells == len(cut.cells) and np.array_equal(np.asarray(g.points), cut.points)
    for i in range(g.n_cells):
        surf = g.extract_cells([i]).extract_surface(algorithm="dataset_surface").triangulate()
        assert surf.n_open_edges == 0, i
        assert abs(surf.volume - g.cell_data["volume"][i]) <= 1e-9 * volume, i
    g.save(tmp_path / "pv.vtu")
    back = pv.read(tmp_path / "pv.vtu")
    assert back.n_cells == g.n_cells and np.array_equal(np.asarray(back.cell_data["cell_id"]), np.arange(g.n_cells))

    m = cut.to_meshio()
    ids = np.concatenate(m.cell_data["cell_id"])
    assert sorted(ids.tolist()) == list(range(len(cut.cells)))
    assert np.array_equal(np.concatenate(m.cell_data["volume"]), cut.cell_volumes[ids])
    for block in m.cells:  # polyhedron<N>: N distinct points per cell
        n = int(block.type[len("polyhedron"):])
        assert all(len(np.unique(np.concatenate(c))) == n for c in block.data)
    meshio.write(tmp_path / "mio.vtu", m)
    again = meshio.read(tmp_path / "mio.vtu")
    assert [b.type for b in again.cells] == [b.type for b in m.cells]
    assert np.array_equal(np.concatenate(again.cell_data["cell_id"]), ids)
    assert np.array_equal(again.points, cut.points)
    back = pv.read(tmp_path / "mio.vtu")
    assert back.n_cells == len(cut.cells)
    order = np.argsort(np.asarray(back.cell_data["cell_id"]))
    for i, j in enumerate(order):
        surf = back.extract_cells([j]).extract_surface(algorithm="dataset_surface").triangulate()
        assert surf.n_open_edges == 0 and abs(surf.volume - cut.cell_volumes[i]) <= 1e-9 * volume, i


def test_obj_and_viewer(case, tmp_path):
    cut, _, _ = case
    path = cut.save(tmp_path / "cells.obj")
    groups = [ln.split()[1] for ln in path.read_text().splitlines() if ln.startswith("g ")]
    assert groups == [f"cell_{i}" for i in range(len(cut.cells))]
    n_faces = sum(ln.startswith("f ") for ln in path.read_text().splitlines())
    assert n_faces == sum(len(c) for c in cut.cell_polygons())
    index = septa.view(cut, tmp_path / "viewer", open=False)
    text = (index.parent / "data.js").read_text()
    data = json.loads(text[text.index("=") + 1:].rstrip().rstrip(";"))
    net = data["network"]
    assert net["mode"] == "cut" and len(net["cells"]) == len(cut.cells)
    assert len(net["faces"]) == n_faces and len(net["points"]) == len(cut.points)


def test_save_refuses_an_unknown_format(tmp_path):
    v, t, _ = hollow_cube()
    cut = septa.cut_mesh(v, t, [[0, 0, 1, -2]])
    with pytest.raises(septa.InputError, match="format"):
        cut.save(tmp_path / "cells.xyz")


foamlib = pytest.importorskip("foamlib")
fluidfoam = pytest.importorskip("fluidfoam")


def _foam(case_dir, name):
    return foamlib.FoamFile(case_dir / "constant" / "polyMesh" / name)


@pytest.mark.parametrize("which", ["hollow", "sphere"])
def test_openfoam_polymesh_reads_back(which, tmp_path):
    if which == "hollow":  # two families: z = 2, z = 3.5 and x = 0.5
        v, t, volume = hollow_cube()
        planes = np.array([[0, 0, 1, -2], [1, 0, 0, -0.5], [0, 0, -2, 7]], float)
    else:
        v, t, volume = sphere()
        planes = random_planes(7, 11)
    cut = septa.cut_mesh(v, t, planes)
    poly = cut.save(tmp_path / "case" / "constant" / "polyMesh")
    assert poly == tmp_path / "case" / "constant" / "polyMesh"
    case_dir = tmp_path / "case"
    points = np.asarray(_foam(case_dir, "points")[None], float)
    assert np.array_equal(points, cut.points)  # the same doubles
    faces = [np.asarray(f, np.int64) for f in _foam(case_dir, "faces")[None]]
    owner = np.asarray(_foam(case_dir, "owner")[None], np.int64)
    neighbour = np.asarray(_foam(case_dir, "neighbour")[None], np.int64)
    boundary = _foam(case_dir, "boundary")[None]
    boundary = dict(boundary) if not isinstance(boundary, dict) else boundary
    n_int, nc = len(neighbour), len(cut.cells)
    cell_of = np.arange(nc)  # polyMesh cell -> cut-cell
    if cut.foam_cells_swapped is not None:
        a, b = cut.foam_cells_swapped
        cell_of[[a, b]] = [b, a]
    assert len(owner) == len(faces)
    assert set(owner.tolist()) | set(neighbour.tolist()) == set(range(nc))
    assert owner.max() == nc - 1  # the owner list alone tells the number of cells
    # OpenFOAM's order: internal faces first, upper-triangular (owner <
    # neighbour, sorted by owner then neighbour), then boundary faces by patch
    assert np.all(owner[:n_int] < neighbour)
    key = owner[:n_int] * nc + neighbour
    assert np.all(np.diff(key) >= 0)
    names = list(boundary)
    families = 2 if which == "hollow" else 7
    assert names == ["surface"] + [f"planes{k}" for k in range(families)]
    assert boundary["surface"]["type"] == "wall"
    assert boundary["surface"]["startFace"] == n_int and boundary["surface"]["nFaces"] == len(faces) - n_int
    assert all(boundary[n]["nFaces"] == 0 for n in names[1:])
    # the faces are the written polygons: one per polygon of an interior
    # face, one per polygon of a surface face
    n_poly = np.array([len(p) for p in cut.face_polygons])
    interior = cut.face_plane >= 0
    assert n_int == n_poly[interior].sum() and len(faces) - n_int == n_poly[~interior].sum()
    # closed cells: oriented area vectors sum to zero, directed edges cancel,
    # and the divergence theorem gives each cell's volume (so normals point
    # out of the owner)
    area = np.zeros((nc, 3))
    vol = np.zeros(nc)
    edges = [Counter() for _ in range(nc)]
    for i, f in enumerate(faces):
        x = points[f]
        a = 0.5 * sum(np.cross(x[k], x[(k + 1) % len(x)]) for k in range(len(x)))
        w = sum(np.dot(x[0], np.cross(x[k], x[k + 1])) for k in range(1, len(x) - 1)) / 6
        sides = [(owner[i], f.tolist())] + ([(neighbour[i], f[::-1].tolist())] if i < n_int else [])
        for sgn, (c, loop) in zip((1, -1), sides):
            area[c] += sgn * a
            vol[c] += sgn * w
            for p, q in zip(loop, loop[1:] + loop[:1]):
                edges[c][(p, q)] += 1
    scale = np.abs(points).max() ** 2
    assert np.abs(area).max() <= 1e-12 * scale
    assert all(all(e[(q, p)] == n for (p, q), n in e.items()) for e in edges)
    assert np.allclose(vol, cut.cell_volumes[cell_of], rtol=0, atol=1e-12 * volume)
    assert abs(vol.sum() - volume) <= 1e-12 * volume
    # face zones: the internal faces of each plane family, flipMap against
    # the family's first plane normal
    zones = _foam(case_dir, "faceZones")[None]
    assert [z[0] for z in zones] == [f"planes{k}" for k in range(families)]
    family_normal = planes[[0, 1]] if which == "hollow" else planes
    family_of_plane = [0, 1, 0] if which == "hollow" else list(range(7))
    for k, (_, z) in enumerate(zones):
        labels, flips = np.asarray(z["faceLabels"][1]), np.asarray(z["flipMap"][1])
        on_family = np.isin(cut.face_plane, [p for p, f in enumerate(family_of_plane) if f == k])
        assert len(labels) == n_poly[on_family].sum() and np.all(labels < n_int)
        for i, flip in zip(labels, flips):
            x = points[faces[i]]
            n = sum(np.cross(x[j], x[(j + 1) % len(x)]) for j in range(len(x)))
            assert np.dot(n, family_normal[k, :3]) * (1 - 2 * flip) > 0, (k, i)
    # a maintained reader of the whole case: one cell centre per cell, one
    # face centre per face of the surface patch
    x, y, z = fluidfoam.readmesh(str(case_dir), verbose=False)
    assert len(x) == nc
    bx, by, bz = fluidfoam.readmesh(str(case_dir), boundary="surface", verbose=False)
    assert len(bx) == len(faces) - n_int


def test_command_line_writes_the_same_polymesh(tmp_path):
    import subprocess
    from pathlib import Path

    septa_bin = Path(__file__).resolve().parents[2] / "target" / "release" / "septa"
    assert septa_bin.exists(), "the command line is built by scripts/test.sh first"
    v, t, _ = sphere()
    (tmp_path / "ball.obj").write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
                                       + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in t.tolist()))
    planes = random_planes(7, 11)
    (tmp_path / "p.plane").write_text("".join(" ".join(repr(float(x)) for x in p) + "\n" for p in planes))
    subprocess.run([str(septa_bin), "cut", str(tmp_path / "ball.obj"), "--planes", str(tmp_path / "p.plane"),
                    "--format", "foam,vtu", "-o", str(tmp_path / "out"), "--json"], check=True, capture_output=True)
    out = tmp_path / "out"
    assert (out / "cells.vtu").exists() and not (out / "cells.obj").exists()
    manifest = json.loads((out / "manifest.json").read_text())
    assert {f"constant/polyMesh/{n}" for n in ("points", "faces", "owner", "neighbour", "boundary", "faceZones")} \
        <= {f["name"] for f in manifest["files"]}
    cut = septa.cut_mesh(v, t, planes)
    mine = cut.save_foam(tmp_path / "py")
    for name in ("points", "faces", "owner", "neighbour", "boundary", "faceZones"):
        assert (out / "constant" / "polyMesh" / name).read_bytes() == (mine / name).read_bytes(), name
    info = json.loads((out / "cut.json").read_text())
    assert info["foam_cells_swapped"] == (list(cut.foam_cells_swapped) if cut.foam_cells_swapped else None)


def test_progress_reports_every_stage_and_keeps_the_result():
    # progress(done, total) once per stage, in order, ending at total; the
    # result is the one without a callback.
    v, t, _ = hollow_cube()
    planes = [[0, 0, 1, -2], [1, 0, 0, -0.5]]
    calls = []
    with_cb = septa.cut_mesh(v, t, planes, progress=lambda done, total: calls.append((done, total)))
    plain = septa.cut_mesh(v, t, planes)
    total = calls[-1][1]
    assert total > 5 and calls == [(i, total) for i in range(1, total + 1)]
    assert with_cb.summary()["cut_cells"] == plain.summary()["cut_cells"]
    assert np.array_equal(with_cb.points, plain.points)
    with pytest.raises(septa.InputError, match="progress"):
        septa.cut_mesh(v, t, planes, progress=3)
