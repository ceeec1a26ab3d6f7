"""masav.Sph: the same run as `masav sph`, CSV byte for byte and its values from the Python state
on the CPU backend; checkpoints that resume bit for bit (and are the command line's); the CPU
views of the state; Ctrl-C; bad options."""
import glob
import os
import subprocess
import threading
import _thread

import numpy as np
import pytest

import masav

RUN = dict(preset="dambreak", particles=500)


def g9(x):
    """A value as the CSV writes it (fmt's {:.9g})."""
    return format(float(x), ".9g")


def test_csv_is_the_command_lines_byte_for_byte(cpu, masav_cli, tmp_path):
    cli_csv, py_csv = tmp_path / "cli.csv", tmp_path / "py.csv"
    subprocess.run([masav_cli, "sph", "--backend", "cpu", "--preset", "dambreak", "--particles",
                    "500", "--steps", "20", "--csv", str(cli_csv), "-q"], check=True,
                   capture_output=True)
    sim = masav.Sph(cpu, **RUN)
    r = sim.run(steps=20, csv=str(py_csv))
    assert r["steps"] == 20 and r["csv_rows"] == 21
    assert py_csv.read_bytes() == cli_csv.read_bytes()

    # The last row from the Python state: the same sums in the same order (sequential, by id).
    header, *rows = py_csv.read_text().splitlines()
    row = dict(zip(header.split(","), rows[-1].split(",")))
    st = sim.download()
    fluid = sim.layout["fluid"]
    m = sim.layout["mass"]
    x, v = st["positions"], st["velocities"]
    assert row["step"] == g9(sim.steps) and row["time_s"] == g9(sim.time)
    moving = x[:, 3] > 0
    speed = np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1] + v[:, 2] * v[:, 2])
    assert row["max_speed"] == g9(speed[moving].max())
    fluid_mass = np.cumsum(np.full(fluid, m))[-1]
    for axis, name in enumerate(("com_x", "com_y", "com_z")):
        assert row[name] == g9(np.cumsum(m * x[:fluid, axis])[-1] / fluid_mass)
    assert row["mean_density"] == g9(np.cumsum(st["density"][:fluid])[-1] / fluid)
    assert row["max_density"] == g9(st["density"][:fluid].max())


def test_checkpoint_resumes_bit_for_bit(cpu, tmp_path):
    whole = masav.Sph(cpu, **RUN)
    whole.run(steps=24)
    first = masav.Sph(cpu, **RUN)
    first.run(steps=10)
    path = first.checkpoint(str(tmp_path / "ck"))
    assert os.path.exists(path)
    resumed = masav.Sph.restore(cpu, str(tmp_path / "ck"))
    assert resumed.steps == 10 and resumed.time == first.time
    resumed.run(steps=14)
    a, b = whole.download(), resumed.download()
    assert resumed.steps == whole.steps and resumed.time == whole.time
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)


def test_a_command_line_checkpoint_resumes_in_python(cpu, masav_cli, tmp_path):
    subprocess.run([masav_cli, "sph", "--backend", "cpu", "--preset", "dambreak", "--particles",
                    "500", "--steps", "10", "--checkpoint-dir", str(tmp_path), "-q"], check=True,
                   capture_output=True)
    resumed = masav.Sph.restore(cpu, str(tmp_path))
    resumed.run(steps=6)
    whole = masav.Sph(cpu, **RUN)
    whole.run(steps=16)
    np.testing.assert_array_equal(resumed.download()["positions"], whole.download()["positions"])


def test_cpu_views_are_the_simulations_own_arrays(cpu):
    sim = masav.Sph(cpu, **RUN)
    sim.run(steps=4)
    ids = sim.ids
    st = sim.download()
    np.testing.assert_array_equal(sim.positions, st["positions"][ids])
    np.testing.assert_array_equal(sim.velocities, st["velocities"][ids])
    assert sorted(ids) == list(range(sim.particle_count))
    # A write through the view is the simulation's state: download() reads it back.
    view = sim.velocities
    view[:, :3] = 0.25
    np.testing.assert_array_equal(sim.download()["velocities"][:, :3], 0.25)
    # The state buffers go to kernels as they are: the grid of the simulation's own positions.
    grid = masav.make_grid_params((0, 0, 0), 0.1, (10, 10, 10), sim.particle_count)
    n = sim.particle_count
    cells, idx = np.zeros(n, np.uint32), np.zeros(n, np.uint32)
    cpu.grid_assign_cells(grid, sim.buffer("positions"), cells, idx)
    want, idx2 = np.zeros(n, np.uint32), np.zeros(n, np.uint32)
    cpu.grid_assign_cells(grid, np.ascontiguousarray(sim.positions), want, idx2)
    np.testing.assert_array_equal(cells, want)


def test_device_backends_download(vulkan):
    sim = masav.Sph(vulkan, preset="dambreak", particles=300)
    sim.step()
    assert sim.download()["positions"].shape == (sim.particle_count, 4)
    with pytest.raises(masav.Error, match="download"):
        sim.positions
    assert sim.buffer("density").kind == "real"


def test_ctrl_c_stops_at_a_whole_step_and_leaves_it_usable(cpu, tmp_path):
    sim = masav.Sph(cpu, **RUN)
    partial = str(tmp_path / ".*.masav-partial")

    def interrupt_once_rows_appear():
        # The CSV's rows reach its partial file as their steps end: the run is stepping.
        while True:
            files = glob.glob(partial)
            if files and open(files[0]).read().count("\n") >= 3:
                _thread.interrupt_main()
                return

    t = threading.Thread(target=interrupt_once_rows_appear, daemon=True)
    t.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run(steps=20000, csv=str(tmp_path / "sph.csv"), checkpoint_dir=str(tmp_path / "ck"))
    t.join()
    stopped = sim.steps
    assert 0 < stopped < 20000
    # The checkpoint and the CSV of the interrupted run are whole, at the step it stopped at.
    assert masav.Sph.restore(cpu, str(tmp_path / "ck")).steps == stopped
    assert (tmp_path / "sph.csv").read_text().count("\n") == 1 + stopped + 1  # header, step 0..
    sim.step()
    sim.run(steps=3)
    assert sim.steps == stopped + 4


def test_run_to_a_time(cpu):
    sim = masav.Sph(cpu, **RUN)
    sim.run(t_end=0.004)
    assert sim.time >= 0.004 and sim.steps > 0


def test_an_earlier_runs_snapshots_are_refused_unless_overwrite(cpu, tmp_path):
    out = str(tmp_path / "snaps")
    masav.Sph(cpu, **RUN).run(steps=4, out_dir=out, vtp_every=1)
    (tmp_path / "snaps" / "notes.txt").write_text("mine")
    with pytest.raises(masav.Error, match="earlier run"):
        masav.Sph(cpu, **RUN).run(steps=2, out_dir=out, vtp_every=1)
    masav.Sph(cpu, **RUN).run(steps=2, out_dir=out, vtp_every=1, overwrite=True)
    assert len(glob.glob(os.path.join(out, "*.vtp"))) == 3  # steps 0, 1, 2 of the new run
    assert (tmp_path / "snaps" / "notes.txt").read_text() == "mine"


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(preset="lava"), "lava"),
        (dict(particles=0), "invalid particles = 0"),
        (dict(kp=5.0), "kp conflicts with the wcsph pressure model"),
        (dict(pressure="dfsph", sound_speed=20.0), "sound_speed conflicts with the dfsph"),
        (dict(seed=3), "seed changes nothing"),
        (dict(dt=-1.0), "dt"),
        (dict(integrator="rk5"), "rk5"),
    ],
)
def test_bad_options_are_refused_by_name(cpu, kwargs, message):
    with pytest.raises(masav.Error, match=message):
        masav.Sph(cpu, **{**dict(particles=300), **kwargs})


def test_bad_run_arguments(cpu):
    sim = masav.Sph(cpu, particles=300)
    with pytest.raises(masav.Error, match="exactly one"):
        sim.run()
    with pytest.raises(masav.Error, match="exactly one"):
        sim.run(steps=3, t_end=1.0)
    with pytest.raises(masav.Error, match="invalid steps = 0"):
        sim.run(steps=0)
    with pytest.raises(masav.Error, match="invalid t_end = nan"):
        sim.run(t_end=float("nan"))
