"""Regions as solids (net.region: closed, outward, own vertices; through a
float32 STL and back with trimesh) and net.to_pyvista() equal to the .vtm
written by the command line's writer, arrays included."""
import numpy as np
import pytest
import septa

trimesh = pytest.importorskip("trimesh")
pv = pytest.importorskip("pyvista")


def _stl_round_trip(v, t, path):
    """Binary STL (float32, no shared vertices) and back, merged by trimesh."""
    trimesh.Trimesh(vertices=v, faces=t, process=False).export(path)
    return trimesh.load(path)  # process=True: merges the triangles' corners


def _check_solid(net, key, cell):
    v, t = net.region(key)
    assert len(v) == len(np.unique(t)) <= len(net.points)  # only its own vertices
    m = net.region(key, to="trimesh")
    assert m.is_watertight and m.is_winding_consistent
    assert m.volume > 0  # outward
    assert m.volume == pytest.approx(net.cell_volume[cell], rel=1e-12)
    return v, t


def test_cad_part_solid_through_stl(tmp_path):
    net = septa.region_surfaces("builtin:cad-part")
    inside = [c for c, n in net.names["regions"].items() if n != "outside"]
    assert inside, net.names
    for cell in inside:
        v, t = _check_solid(net, net.names["regions"][cell], cell)
        assert len(v) < len(net.points)
        # the certified embedding nudged coincident points apart by ulps:
        # some meet again in float32, and the float32 surface merges them
        assert len(np.unique(v.astype(np.float32), axis=0)) < len(v)
        v, t = net.region(cell, dtype=np.float32)
        assert v.dtype == np.float32
        back = _stl_round_trip(v, t, tmp_path / f"{cell}.stl")
        assert back.is_watertight and back.is_winding_consistent
        assert len(back.faces) == len(t) and len(back.vertices) == len(v)
        # float32 coordinates: a relative error of ~6e-8 per coordinate
        assert back.volume == pytest.approx(net.cell_volume[cell], rel=1e-5)
    # the outside holds the box's boundary: its closed surface bounds the part, said so
    with pytest.raises(septa.InputError, match="reaches the domain's box"):
        net.region("outside")
    v, t = net.region("outside", closed=False)
    assert trimesh.Trimesh(vertices=v, faces=t, process=False).volume == pytest.approx(-net.cell_volume[1])
    with pytest.raises(septa.InputError, match="no region of that name"):
        net.region("nope")
    with pytest.raises(septa.InputError, match="no such region"):
        net.region(len(net.cells))


def test_save_regions_one_stl_per_closed_region(tmp_path):
    net = septa.region_surfaces([{"name": "ball", "type": "sphere", "center": [0.01, -0.02, 0.03], "radius": 0.5}],
                                "ball", grid={"resolution": 16, "bounds": [[-1] * 3, [1] * 3]})
    written = net.save_regions(tmp_path / "solids")
    assert {c: p.name for c, p in written.items()} == {1: "inside.stl"}  # outside reaches the box
    back = trimesh.load(written[1])
    assert back.is_watertight and back.volume == pytest.approx(net.cell_volume[1], rel=1e-5)
    assert sorted(p.name for p in (tmp_path / "solids").iterdir()) == ["inside.stl"]  # no temporary left


def test_arrangement_and_label_cells_as_solids(tmp_path):
    from septa import shapes

    g = septa.grid.box(20)
    f = shapes.sample([shapes.sphere([0.5] * 3, 0.3), shapes.sphere([0.62, 0.5, 0.5], 0.25)], g)
    net = septa.arrangement(g, f)
    closed = 0
    for c in range(len(net.cells)):
        try:
            v, t = _check_solid(net, c, c)
        except septa.InputError:
            continue  # the cell around both spheres reaches the box
        closed += 1
        back = _stl_round_trip(*net.region(c, dtype=np.float32), tmp_path / f"{c}.stl")
        assert back.is_watertight and back.volume == pytest.approx(net.cell_volume[c], rel=1e-5)
    assert closed == 3  # the two spheres' lens and their two other parts
    vol = np.zeros((14, 13, 12), dtype=np.int32)
    z, y, x = np.mgrid[:14, :13, :12]
    vol[(z - 6.5) ** 2 + (y - 6) ** 2 + (x - 5.5) ** 2 < 16] = 1
    labels = septa.label_surfaces(vol, names={1: "ball"})
    assert labels.names["regions"] == {1: "ball"}
    _check_solid(labels, "ball", 1)
    with pytest.raises(septa.InputError, match="not an integer label"):
        septa.label_surfaces(vol, names={"1": "ball"})


def _cells(block):
    g = block.cast_to_unstructured_grid()
    return g.points, g.cells, {k: np.asarray(g.cell_data[k]) for k in g.cell_data.keys()}


@pytest.mark.parametrize("scene", ["builtin:box-minus-cylinder", "arrangement"])
def test_to_pyvista_equals_the_vtm(scene, tmp_path):
    if scene == "arrangement":
        from septa import shapes

        g = septa.grid.box(12)
        net = septa.arrangement(g, shapes.sample([shapes.sphere([0.5] * 3, 0.3), shapes.plane([0.5] * 3, [0, 0, 1])], g))
    else:
        net = septa.region_surfaces(scene)
    net.save(tmp_path / "n.vtm")
    written, mb = pv.read(tmp_path / "n.vtm"), net.to_pyvista()
    assert list(mb.keys()) == list(written.keys())
    for name in written.keys():
        (p0, c0, d0), (p1, c1, d1) = _cells(written[name]), _cells(mb[name])
        assert np.array_equal(p0, p1) and np.array_equal(c0, c1), name
        assert sorted(d0) == sorted(d1), name
        for k in d0:
            if d0[k].dtype.kind == "f":
                assert np.allclose(d0[k], d1[k], rtol=1e-12, atol=0), (name, k)
            else:
                assert np.array_equal(d0[k], d1[k]), (name, k)


def test_load_of_a_json_only_folder_keeps_face_ids(tmp_path):
    net = septa.region_surfaces("builtin:box-minus-cylinder")
    (tmp_path / "r").mkdir()
    net.save(tmp_path / "r" / "network.json")
    back = septa.load(tmp_path / "r")
    assert back.source.name == "network.json"
    assert np.array_equal(back.face_label, net.face_label) and np.array_equal(back.face_cells, net.face_cells)
    assert (back.face_label >= 0).all()
