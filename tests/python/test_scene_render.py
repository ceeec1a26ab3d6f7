"""Scene files rendered headless through masav.SceneRenderer: the same frames, byte for byte,
as `masav run` writes, on the CPU reference (drawn on a Vulkan device of its own) and on Vulkan
(drawn where its buffers lie); bad arguments refused by name."""
import subprocess

import numpy as np
import pytest

import masav
from conftest import REQUIRED

SPH = """
[scene]
type = "sph"
[sph]
preset = "water"
count = 600
substeps = 8
[render]
width = 64
height = 48
point_size = 3.0
[verify]
max_points = 512
"""


def renderer(backend, **kw):
    try:
        return masav.SceneRenderer(masav.parse_scene(SPH), backend=backend, **kw)
    except masav.Error as e:
        # No Vulkan device to draw with: a skip where Vulkan is not required, never a pass.
        if "vulkan" in REQUIRED or "ulkan" not in str(e):
            raise
        pytest.skip(f"no Vulkan device to draw with: {e}")


@pytest.mark.parametrize("backend", ["cpu", "vulkan"])
def test_frames_are_the_frames_masav_run_writes(backend, masav_cli, tmp_path):
    if backend == "vulkan":
        status = {s.name: s for s in masav.backends()}["vulkan"]
        if not status.available and "vulkan" not in REQUIRED:
            pytest.skip(f"vulkan absent: {status.reason}")
    r = renderer(backend)
    assert (r.width, r.height, r.backend) == (64, 48, backend)
    assert r.shares_device == (backend == "vulkan")
    frames = [r.next_frame() for _ in range(3)]
    assert r.frames_drawn == 3
    for i, f in enumerate(frames):
        assert f.shape == (48, 64, 4) and f.dtype == np.uint8
        masav.save_png(str(tmp_path / f"api_{i}.png"), f)
    # The water falls: every frame differs from the one before, and something is drawn.
    assert all((a != b).any() for a, b in zip(frames, frames[1:]))
    assert (frames[0][..., :3] != frames[0][0, 0, :3]).any()

    scene = tmp_path / "scene.toml"
    scene.write_text(SPH)
    out = tmp_path / "run"
    subprocess.run([masav_cli, "run", str(scene), "--backend", backend, "--frames", "3",
                    "--no-video", "--no-verify", "--out", str(out)], check=True,
                   capture_output=True, timeout=300)
    for i in range(3):
        assert (out / f"frame_{i:05d}.png").read_bytes() == (tmp_path / f"api_{i}.png").read_bytes()


def test_verify_runs_the_scene_cross_check():
    report = renderer("cpu").verify()
    assert report.passed, report.text


def test_bad_arguments_are_refused_by_name(tmp_path):
    with pytest.raises(masav.Error, match="tune"):
        masav.SceneRenderer(masav.parse_scene(SPH), backend="cpu", tune="cpu.threads=2")
    with pytest.raises(masav.Error, match="cpu.thread"):
        masav.SceneRenderer(masav.parse_scene(SPH), backend="cpu", tune={"cpu.thread": 2})
    with pytest.raises(masav.Error, match="libmasav-no-such-loader"):
        masav.SceneRenderer(masav.parse_scene(SPH), backend="cpu",
                            loader="libmasav-no-such-loader.so")
    with pytest.raises(masav.Error, match="does-not-exist.toml"):
        masav.SceneRenderer(str(tmp_path / "does-not-exist.toml"))
    with pytest.raises(masav.Error, match=r"\(height, width, 4\)"):
        masav.save_png(str(tmp_path / "x.png"), np.zeros((4, 4, 3), np.uint8))
    with pytest.raises(masav.Error, match="at least one pixel"):
        masav.save_png(str(tmp_path / "x.png"), np.zeros((0, 4, 4), np.uint8))
    assert not (tmp_path / "x.png").exists()
