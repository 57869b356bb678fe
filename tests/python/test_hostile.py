"""Hostile files in Python: ``septa.load`` checks every array and
names the file and the array; writers never replace a link, FIFO or device;
deep region rules are an error, not a dead kernel. FIFOs and links are made
in temporary folders only."""
import json
import os
import shutil

import numpy as np
import pytest

import septa
from conftest import FIXTURE


def _fixture(tmp_path):
    d = tmp_path / "r"
    shutil.copytree(FIXTURE, d)
    return d, json.loads((d / "network.json").read_text())


@pytest.mark.parametrize("change, array", [
    (lambda n: n.update(points=[p[:2] for p in n["points"]]), "points"),
    (lambda n: n.update(face_label=[[0] for _ in n["faces"]]), "face_label"),
    (lambda n: n.update(faces=[[i + 0.5 for i in f] for f in n["faces"]]), "faces"),
    (lambda n: n.update(faces=[[0, 1, 10**9]]), "faces"),
    (lambda n: n.update(points=[[0, 0, "x"]]), "points"),
    (lambda n: n.update(cells=[{"shells": [10**12]}]), "cells"),
    (lambda n: n.update(patches="nope"), "patches"),
    (lambda n: n.update(face_label=[[1, 2], [3]]), "face_label"),
])
def test_load_checks_every_json_array(tmp_path, change, array):
    d, net = _fixture(tmp_path)
    change(net)
    (d / "network.json").write_text(json.dumps(net))
    with pytest.raises(septa.InputError, match=f"network.json: .*'{array}'|network.json: not a septa network"):
        septa.load(d)


def test_load_names_the_file_for_broken_json(tmp_path):
    d, _ = _fixture(tmp_path)
    (d / "network.json").write_text("[" * 100000)
    with pytest.raises(septa.InputError, match="network.json"):
        septa.load(d)
    (d / "network.json").write_text('{"points": [], "faces": {"a": 1}}')
    with pytest.raises(septa.InputError, match="network.json.*'faces'"):
        septa.load(d)


def test_load_checks_every_npz_array(tmp_path):
    net = septa.load(FIXTURE)
    good = tmp_path / "good.npz"
    net.save(good)
    base = dict(np.load(good, allow_pickle=False))
    assert len(septa.load(good)) == len(net)
    bad = {
        "points": base["points"][:, :2],
        "indices": base["indices"].astype(np.float64) + 0.5,
        "shell_offsets": np.array([0, 10**12], dtype=np.int64),
        "labels": base["labels"][:, :1],
        "meta": np.array("{not json"),
    }
    for name, value in bad.items():
        arrays = dict(base, **{name: value})
        p = tmp_path / f"bad-{name}.npz"
        np.savez(p, **arrays)
        with pytest.raises(septa.InputError, match=f"bad-{name}.npz: .*'{name}'"):
            septa.load(p)


def test_load_refuses_special_files(tmp_path):
    d, _ = _fixture(tmp_path)
    (d / "network.json").unlink()
    os.mkfifo(d / "network.json")
    with pytest.raises(septa.InputError, match="FIFO"):
        septa.load(d)


def test_writers_never_replace_links_or_fifos(tmp_path):
    net = septa.load(FIXTURE)
    victim = tmp_path / "victim.txt"
    victim.write_text("keep")
    for ext in (".ply", ".json", ".npz"):
        link = tmp_path / f"link{ext}"
        link.symlink_to(victim)
        with pytest.raises(septa.InputError, match="symbolic link"):
            net.save(link)
        assert link.is_symlink() and victim.read_text() == "keep"
        fifo = tmp_path / f"fifo{ext}"
        os.mkfifo(fifo)
        with pytest.raises(septa.InputError, match="FIFO"):
            net.save(fifo)
        assert fifo.is_fifo()
    spec = [{"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]
    os.mkfifo(tmp_path / "s.ply")
    with pytest.raises((septa.InputError, OSError), match="FIFO"):
        septa.stream.stream_ply(spec, tmp_path / "s.ply", grid=8, block=4)
    assert (tmp_path / "s.ply").is_fifo()
    # nothing hidden left behind
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".tmp")]


def test_deep_region_rules_are_an_error_not_a_crash():
    functions = [{"name": "a", "type": "sphere", "center": [0, 0, 0], "radius": 0.5}]
    grid = {"resolution": 4, "bounds": [[-1] * 3, [1] * 3]}
    for rule, what in (("!" * 1_000_000 + "a", "longer than"), ("(" * 20_000 + "a" + ")" * 20_000, "nested deeper")):
        with pytest.raises(septa.InputError, match=what):
            septa.region_surfaces(functions, rule, grid=grid)


def test_inline_viewer_escapes_script_ends_in_any_case():
    from septa.viewer import inline_html
    import html as h

    net = septa.load(FIXTURE)
    plain = h.unescape(inline_html(net)).lower().count("</script")
    net._counts["note"] = "</SCRIPT><script>alert(1)</script></ScRiPt >"
    net._data = None
    page = h.unescape(inline_html(net))
    assert page.lower().count("</script") == plain
    assert "alert(1)" in page  # the text is kept, escaped
