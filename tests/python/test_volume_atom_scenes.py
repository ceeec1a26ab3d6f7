"""Volumes raymarched to (H, W, 4) arrays on both backends, volume files, the atom pipeline and
scene files."""
import numpy as np
import pytest

import masav


def ball(n=24):
    z, y, x = np.meshgrid(*(np.linspace(-1, 1, n),) * 3, indexing="ij")
    return np.clip(1.0 - np.sqrt(x * x + y * y + z * z), 0, 1).astype(np.float32)


def test_raymarch_is_an_image_and_agrees_across_backends(cpu, vulkan):
    want = masav.raymarch(cpu, ball(), width=40, height=30)
    got = masav.raymarch(vulkan, ball(), width=40, height=30)
    assert want.shape == got.shape == (30, 40, 4)
    assert want[15, 20, 3] > 0.1 and want[0, 0, 3] == 0  # the ball in the middle, none at corners
    v = masav.compare_outputs("raymarch", {"image": got.ravel()}, {"image": want.ravel()})
    assert v["passed"], v["metrics"]


def test_raymarch_refuses_bad_volumes(cpu):
    v = ball(8)
    v[1, 2, 3] = np.nan
    with pytest.raises(masav.Error, match="element .* is nan"):
        masav.raymarch(cpu, v)
    with pytest.raises(masav.Error, match="invalid ndim = 2"):
        masav.raymarch(cpu, np.zeros((8, 8), np.float32))
    with pytest.raises(masav.Error, match=r"invalid shape\[0\] = 1"):
        masav.raymarch(cpu, np.zeros((1, 8, 8), np.float32))
    with pytest.raises(masav.Error, match="invalid dtype = int32"):
        masav.raymarch(cpu, np.zeros((8, 8, 8), np.int32))
    with pytest.raises(masav.Error, match="mode"):
        masav.raymarch(cpu, ball(8), mode="max")


def test_volume_files_and_transfer_functions(cpu, source_dir):
    values, info = masav.load_volume(str(source_dir / "tests" / "data" / "tiny_4x4x4.nrrd"))
    assert values.shape == (4, 4, 4) and values.dtype == np.float32
    assert info["min"] <= values.min() and values.max() <= info["max"]
    tf = masav.transfer_function()
    assert tf.shape == (256, 4) and 0 <= tf.min() and tf.max() <= 1
    image = masav.raymarch(cpu, values, width=16, height=16, transfer=tf)
    assert image.shape == (16, 16, 4)
    with pytest.raises(masav.Error, match="character device"):
        masav.load_volume("/dev/zero", dims=[8, 8, 8], type="uint8")


def test_atom_pipeline_runs_and_raymarches(cpu):
    a = masav.Atom(cpu, state="state2", particles=3000, density_dims=16, volume_dims=16,
                   photons=128, use_cache=False)
    with pytest.raises(masav.Error, match="build_cloud"):
        a.positions
    a.run()
    assert a.positions.shape == (3000, 4)
    assert a.volume.shape == (16, 16, 16) and 0 <= a.volume.min() and a.volume.max() <= 1
    image = a.raymarch(width=32, height=24)
    assert image.shape == (24, 32, 4) and image[..., 3].max() > 0
    with pytest.raises(masav.Error, match="state"):
        masav.Atom(cpu, state="state11")


def test_scene_files(cpu, vulkan, source_dir):
    s = masav.load_scene(str(source_dir / "scenes" / "particles.toml"),
                         set={"particles.count": 2000})
    assert s.type == "particles" and s["particles.count"] == 2000
    assert "particles.count" in s.keys() and "count = 2000" in s.toml
    assert "drift_points" in masav.scene_kernels(s)
    with pytest.raises(masav.Error, match="particles.cont"):
        s.set({"particles.cont": 3})
    r = masav.cross_check_scene(s, vulkan, cpu)
    assert r.passed and r.points > 0, r.text
    assert "sph" in [t for t, _ in masav.scene_types()]
