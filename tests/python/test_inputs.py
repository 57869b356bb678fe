"""Inputs as users have them: coercion that never truncates,
thread counts checked, unreadable results as InputError, label volumes of
any dtype and order, and NIfTI / NRRD files placed where nibabel says,
with flips (negative determinant) keeping every polygon's orientation."""
import numpy as np
import pytest

import septa


def _tet():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    t = np.array([[0, 1, 2, 3]])
    f = (v - 0.3).sum(axis=1)
    return v, t, f


def test_fractional_indices_and_threads_are_errors():
    v, t, f = _tet()
    with pytest.raises(septa.InputError, match="tets: element \\(0, 0\\) is 0.7"):
        septa.arrangement(v, t + 0.7, f)
    # Whole-number floats are indices (what np.loadtxt gives).
    assert septa.arrangement(v, t.astype(float), f).summary()["patches"] == 1
    with pytest.raises(septa.InputError, match="threads"):
        septa.arrangement(v, t, f, threads=10**6)
    with pytest.raises(septa.InputError, match="threads"):
        septa.arrangement(v, t, f, threads=0)
    with pytest.raises(septa.InputError, match="0 tets"):
        septa.arrangement(np.zeros((0, 3)), np.zeros((0, 4), int), np.zeros((0, 2)))
    tri = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    with pytest.raises(septa.InputError, match="triangles"):
        septa.cut_mesh(v, tri + 0.5, [[1, 0, 0, -0.25]])


def test_load_binary_and_interrupted_folders(tmp_path):
    (tmp_path / "network.json").write_bytes(b"\x89PNG\xff\x00\x01")
    with pytest.raises(septa.InputError, match="not UTF-8"):
        septa.load(tmp_path)
    (tmp_path / "network.json").write_text('{"points": [], "faces": []}')
    (tmp_path / ".septa.lock").write_text("1\n")
    with pytest.raises(septa.InputError, match="incomplete"):
        septa.load(tmp_path)


def _volume():
    v = np.zeros((6, 7, 8), dtype=np.int16)
    v[1:4, 2:5, 2:7] = 3
    v[3:5, 1:3, 1:4] = 5
    return v


def _signed_volume(net, region):
    """Signed volume enclosed by every polygon bounding ``region``: each is
    counter-clockwise seen from the lesser region of its pair, so flipped
    where ``region`` is the lesser one; the result is then the region's
    volume (closed surface: independent of the origin)."""
    total = 0.0
    for f in range(len(net.offsets) - 1):
        pair = net.patch_labels[net.face_patch[f]].tolist()
        if region not in pair:
            continue
        p = net.points[net.indices[net.offsets[f]:net.offsets[f + 1]]]
        sign = -1.0 if region == min(pair) else 1.0
        for k in range(1, len(p) - 1):
            total += sign * np.dot(p[0], np.cross(p[k], p[k + 1])) / 6.0
    return total


def test_label_dtypes_and_orders_give_one_result():
    v = _volume()
    ref = septa.label_surfaces(v)
    for other in (np.asfortranarray(v), v.astype(">i4"), v.astype(np.float32), v.astype(np.uint8)):
        net = septa.label_surfaces(other)
        assert np.array_equal(net.indices, ref.indices) and net.points.tobytes() == ref.points.tobytes()
    b = septa.label_surfaces(v > 0)
    assert sorted(s["regions"] for s in b.surfaces) == [[0, 1]]


def test_nifti_and_nrrd_affines_land_where_nibabel_says(tmp_path):
    nib = pytest.importorskip("nibabel")
    from nibabel.affines import apply_affine

    v = _volume()
    ref = septa.label_surfaces(v)  # points in voxel index coordinates
    pair = 5
    ref_vol = _signed_volume(ref, pair)
    assert abs(ref_vol) > 1
    c, s = np.cos(0.3), np.sin(0.3)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    cases = {
        "flip-xy": np.diag([-0.8, -0.8, 2.0]),          # det > 0: two flips
        "flip-x": np.diag([-0.8, 0.8, 2.0]),            # det < 0: a mirror
        "rotated-sheared": rot @ np.array([[0.9, 0.2, 0], [0, 1.1, 0], [0, 0, -1.5]]),  # det < 0
    }
    for name, m in cases.items():
        affine = np.eye(4)
        affine[:3, :3] = m
        affine[:3, 3] = [100.0, -20.0, 7.5]
        path = tmp_path / f"{name}.nii.gz"
        nib.save(nib.Nifti1Image(v, affine), str(path))
        net = septa.label_surfaces(path)
        assert np.allclose(net.points, apply_affine(affine, ref.points)), name
        # Orientation kept: the signed volume has the reference's sign, scaled by |det|.
        assert np.isclose(_signed_volume(net, pair), ref_vol * abs(np.linalg.det(m))), name
    nrrd = pytest.importorskip("nrrd")
    m = cases["rotated-sheared"]
    nrrd.write(str(tmp_path / "v.nrrd"), v, {"space directions": m.T, "space origin": [100.0, -20.0, 7.5],
                                             "space": "left-posterior-superior"})
    a = septa.label_surfaces(tmp_path / "v.nrrd")
    affine = np.eye(4)
    affine[:3, :3] = m
    affine[:3, 3] = [100.0, -20.0, 7.5]
    assert np.allclose(a.points, apply_affine(affine, ref.points))
    assert np.isclose(_signed_volume(a, pair), ref_vol * abs(np.linalg.det(m)))


def _cli_labels(tmp_path, path, *extra):
    import subprocess

    from conftest import SEPTA, need

    out = tmp_path / ("out-" + path.name + "-".join(extra))
    r = subprocess.run([str(need(SEPTA, "the septa binary")), "labels", str(path), "--quiet", "-o", str(out), *extra],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return septa.load(out)


def test_cli_places_label_files_like_python_and_nibabel(tmp_path):
    """`septa labels` reads NIfTI (sform, or qform only) and NRRD files and
    places them as nibabel / pynrrd say, giving Python's points and polygons."""
    nib = pytest.importorskip("nibabel")
    nrrd = pytest.importorskip("nrrd")
    from nibabel.affines import apply_affine

    v = _volume()
    ref = septa.label_surfaces(v)
    ref_vol = _signed_volume(ref, 5)
    c, s = np.cos(0.3), np.sin(0.3)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    sheared = rot @ np.array([[0.9, 0.2, 0], [0, 1.1, 0], [0, 0, -1.5]])  # det < 0
    mirrored = rot @ np.diag([0.8, 1.2, -2.0])  # a rotation and zooms with a flip: a qform
    files = []
    for name, m, qform_only in (("sheared.nii.gz", sheared, False), ("flip-x.nii", np.diag([-0.8, 0.8, 2.0]), False),
                                ("qform.nii", mirrored, True)):
        affine = np.eye(4)
        affine[:3, :3] = m
        affine[:3, 3] = [100.0, -20.0, 7.5]
        img = nib.Nifti1Image(v, affine)
        if qform_only:
            img.set_sform(None, code=0)
            img.set_qform(affine, code=1)
        nib.save(img, str(tmp_path / name))
        files.append((tmp_path / name, nib.load(str(tmp_path / name)).affine))
    affine = np.eye(4)
    affine[:3, :3] = sheared
    affine[:3, 3] = [100.0, -20.0, 7.5]
    nrrd.write(str(tmp_path / "v.nrrd"), v, {"space directions": sheared.T, "space origin": [100.0, -20.0, 7.5],
                                             "space": "left-posterior-superior", "encoding": "gzip"})
    files.append((tmp_path / "v.nrrd", affine))
    for path, affine in files:
        cli = _cli_labels(tmp_path, path)
        py = septa.label_surfaces(path)
        assert np.allclose(cli.points, apply_affine(affine, ref.points)), path.name
        assert np.allclose(cli.points, py.points) and np.array_equal(cli.indices, py.indices), path.name
        m = np.asarray(affine)[:3, :3]
        assert np.isclose(_signed_volume(cli, 5), ref_vol * abs(np.linalg.det(m))), path.name
    # --spacing / --origin replace a file's map, as spacing= / origin= do in Python.
    np.save(tmp_path / "v.npy", v)
    cli = _cli_labels(tmp_path, tmp_path / "v.npy", "--spacing", "0.5", "2", "3", "--origin", "-1", "0", "4")
    py = septa.label_surfaces(v, spacing=(0.5, 2, 3), origin=(-1, 0, 4))
    assert np.allclose(cli.points, py.points) and np.array_equal(cli.indices, py.indices)
