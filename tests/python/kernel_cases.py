"""One case per kernel of the kernel list, run through the Python API on any backend.

A case is a function of (backend, inputs) returning the kernel's outputs {name: array}, named
as the kernel's C++ cross-check names them (its per-output tolerances go by those names), so
that masav.compare_outputs judges two backends' outputs with the cross-check's own tolerances.
Inputs are made once on the host (seeded numpy, and the CPU backend for sorted grids) and given
identically to every backend, as the C++ checks do. CASES maps each kernel to its case."""
import numpy as np

import masav

CASES = {}
U32 = np.uint32
C = masav.constants


def case(name):
    def register(f):
        CASES[name] = f
        return f
    return register


def rng(seed=7):
    return np.random.default_rng(seed)


def fbits(a):
    """Float values as the fp32 words an exact check compares."""
    return np.ascontiguousarray(np.asarray(a, dtype=np.float32)).view(U32).ravel()


def xyz(a):
    return np.ascontiguousarray(np.asarray(a)[:, :3]).ravel()


def points_in(grid, n, seed=3):
    """n points uniform in the grid's box, fp32, w = 0."""
    size = np.float32(grid.cell_size) * np.array(grid.dims, dtype=np.float32)
    p = np.zeros((n, 4), dtype=np.float32)
    p[:, :3] = np.array(grid.origin, dtype=np.float32) + rng(seed).random((n, 3), np.float32) * size
    return p


def default_grid(n):
    return masav.make_grid_params((0, 0, 0), 1.0 / 16, (16, 16, 16), n)


def check_grid(kernel):
    ci = masav.check_inputs(kernel)
    g = ci["grid"] or default_grid(ci["points"])
    g.n = ci["points"]
    return ci, g


def prefix_tables(cells, cell_count):
    """Each cell's run in cell order, empty cells as [k, k): what the counting build writes."""
    counts = np.bincount(cells, minlength=cell_count).astype(U32)
    end = np.cumsum(counts, dtype=np.uint64).astype(U32)
    return counts, end - counts, end


def sorted_into(cpu, grid, positions):
    """Positions in cell order (stable), with their cells and the prefix tables, from the CPU
    backend's cell rule."""
    n = len(positions)
    cells, idx = np.zeros(n, U32), np.zeros(n, U32)
    cpu.grid_assign_cells(grid, positions, cells, idx)
    order = np.argsort(cells, kind="stable")
    _, start, end = prefix_tables(cells, masav.grid_cell_count(grid))
    return order, cells[order], start, end


# ---- demo point cloud, random numbers, sorting -----------------------------------------------
@case("drift_points")
def drift_points(b, cpu):
    ci, g = check_grid("drift_points")
    n = ci["points"]
    size = g.cell_size * g.dims[0]
    p = masav.DriftParams(n=n, speed=0.05, time_s=37.5, box_lo=g.origin,
                          box_extent=(size, size, size))
    r = rng(11)
    start, direction = r.random(4 * n, np.float32), r.random(4 * n, np.float32)
    pos = np.zeros((n, 4))
    b.drift_points(p, start, direction, pos)
    return {"positions": pos.ravel()}


@case("philox_u32")
def philox_u32(b, cpu):
    out = np.zeros(4 * 4096, U32)
    b.philox_u32(masav.PhiloxParams(seed=5, stream=7), out)
    return {"words": out}


@case("philox_uniform")
def philox_uniform(b, cpu):
    out = np.zeros(4 * 4096, np.float32)
    b.philox_uniform(masav.PhiloxParams(seed=5, stream=0, first_block=100), out)
    return {"float bits": out.view(U32)}


@case("radix_sort")
def radix_sort(b, cpu):
    n = 20000
    keys = rng(1).integers(0, 1 << 32, n, dtype=np.uint64).astype(U32)
    values = np.arange(n, dtype=U32)
    b.radix_sort(masav.RadixSortParams(n=n, key_bits=32), keys, values)
    assert np.all(keys[:-1] <= keys[1:])
    return {"keys": keys, "values": values}


# ---- the hash grid ----------------------------------------------------------------------------
@case("grid_assign_cells")
def grid_assign_cells(b, cpu):
    g = default_grid(8000)
    cells, idx = np.zeros(8000, U32), np.zeros(8000, U32)
    b.grid_assign_cells(g, points_in(g, 8000), cells, idx)
    return {"cells": cells, "indices": idx}


@case("grid_cell_ranges")
def grid_cell_ranges(b, cpu):
    g = default_grid(8000)
    _, sorted_cells, _, _ = sorted_into(cpu, g, points_in(g, 8000))
    m = masav.grid_cell_count(g)
    start, end = np.zeros(m, U32), np.zeros(m, U32)
    b.grid_cell_ranges(g, sorted_cells, start, end)
    return {"cell start": start, "cell end": end}


@case("gather")
def gather(b, cpu):
    n = 6000
    order = rng(2).permutation(n).astype(U32)
    src = points_in(default_grid(n), n).astype(np.float64)
    dst = np.zeros((n, 4))
    b.gather(masav.GatherParams(n=n), order, src, dst)
    return {"sorted positions (fp32 bits)": fbits(dst)}


@case("grid_count_neighbors")
def grid_count_neighbors(b, cpu):
    g = default_grid(8000)
    pos = points_in(g, 8000)
    order, sorted_cells, _, _ = sorted_into(cpu, g, pos)
    m = masav.grid_cell_count(g)
    start, end = np.zeros(m, U32), np.zeros(m, U32)
    cpu.grid_cell_ranges(g, sorted_cells, start, end)
    counts = np.zeros(8000, U32)
    b.grid_count_neighbors(masav.make_neighbor_params(g, g.cell_size), pos[order], start, end,
                           counts)
    return {"counts": counts}


def cell_ids(n, cell_count, seed=4):
    """Cell ids with every third of the first 3072 points in one hot cell (the atomics contend)."""
    ids = rng(seed).integers(0, cell_count, n).astype(U32)
    hot = np.arange(n)
    ids[(hot % 3 == 0) & (hot < 3072)] = cell_count // 2
    return ids


@case("grid_count_cells")
def grid_count_cells(b, cpu):
    m = 4096
    ids = cell_ids(9000, m)
    counts = np.arange(m, dtype=U32)  # the kernel adds onto what the table holds
    b.grid_count_cells(masav.CellCountParams(n=9000, cell_count=m), ids, counts)
    return {"counts": counts}


@case("grid_assign_count")
def grid_assign_count(b, cpu):
    g = default_grid(8000)
    cells = np.zeros(8000, U32)
    counts = np.arange(masav.grid_cell_count(g), dtype=U32)
    b.grid_assign_count(masav.CellAssignCountParams(grid=g), points_in(g, 8000), cells, counts)
    return {"cells": cells, "counts": counts}


@case("grid_cell_offsets")
def grid_cell_offsets(b, cpu):
    m = 4096
    counts, _, _ = prefix_tables(cell_ids(9000, m), m)
    start, end = np.zeros(m, U32), np.zeros(m, U32)
    b.grid_cell_offsets(masav.CellOffsetParams(cell_count=m), counts, start, end)
    return {"cell start": start, "cell end": end}


@case("grid_scatter_cells")
def grid_scatter_cells(b, cpu):
    m, n = 4096, 9000
    ids = cell_ids(n, m)
    counts, start, end = prefix_tables(ids, m)
    unsorted = np.zeros(n, U32)
    b.grid_scatter_cells(masav.CellScatterParams(n=n, cell_count=m), ids, end, counts, unsorted)
    # The order within a cell depends on timing: each cell's run is compared sorted.
    for c in np.nonzero(end > start)[0]:
        unsorted[start[c]:end[c]].sort()
    return {"each cell's points": unsorted, "counts after": counts}


def rank_inputs(n=9000, m=4096):
    """A host scatter with each cell's run reversed (the order the rank pass must undo)."""
    ids = cell_ids(n, m)
    counts, start, end = prefix_tables(ids, m)
    runs, nxt = np.zeros(n, U32), end.copy()
    for i in range(n):
        nxt[ids[i]] -= 1
        runs[nxt[ids[i]]] = i
    p = masav.CellRankParams(n=n, cell_count=m, max_per_cell=int(counts.max()))
    return p, ids, runs, start, end


@case("grid_rank_in_cell")
def grid_rank_in_cell(b, cpu):
    p, ids, runs, start, end = rank_inputs()
    sc, si = np.zeros(p.n, U32), np.zeros(p.n, U32)
    b.grid_rank_in_cell(p, ids, runs, start, end, sc, si)
    return {"sorted cells": sc, "sorted index": si}


@case("grid_rank_and_move")
def grid_rank_and_move(b, cpu):
    p, ids, runs, start, end = rank_inputs()
    n = p.n
    i = np.arange(n, dtype=np.float64)
    # Integers below 2^24: every backend's precision holds them exactly.
    a = np.stack([i, 2 * i + 1, ids % 4096, np.full(n, 0.5)], axis=1)
    bb = np.stack([-i, i % 977, np.full(n, 3.0), n - i], axis=1)
    id_in = (np.arange(n, dtype=np.uint64) * 2654435761 % (1 << 32)).astype(U32)
    outs = [np.zeros(n, U32), np.zeros(n, U32), np.zeros((n, 4)), np.zeros((n, 4)),
            np.zeros(n, U32)]
    b.grid_rank_and_move(p, ids, runs, start, end, outs[0], outs[1], a, outs[2], bb, outs[3],
                         id_in, outs[4])
    words = lambda v: (v * 2.0).astype(np.int64).astype(U32).ravel()  # noqa: E731
    return {"sorted cells": outs[0], "sorted index": outs[1], "a moved": words(outs[2]),
            "b moved": words(outs[3]), "ids moved": outs[4]}


# ---- SPH: a jittered lattice sorted into its grid (as engine/sph/sph_check_case.cpp) ----------
MODELS = ("wcsph", "thesis", "dfsph")
_sph_cases = {}


def sph_case(cpu, model, side=9):
    key = (model, side)
    if key in _sph_cases:
        return _sph_cases[key]
    dx, h = 0.01, 0.02
    r = rng(21)
    lattice = np.indices((side, side, side)).reshape(3, -1).T[:, ::-1].astype(np.float64)
    n = len(lattice)
    pos = np.zeros((n, 4), np.float32)
    pos[:, :3] = 0.05 + (lattice + 0.3 * r.uniform(-1, 1, (n, 3))) * dx
    s = lattice.sum(axis=1).astype(int)
    heavy = (lattice[:, 0] * lattice[:, 1]).astype(int) % 29 == 1
    pos[:, 3] = np.where(s % 37 == 0, 0.0, np.where(heavy, 1e-3, 1.0))
    vel = np.zeros((n, 4), np.float32)
    vel[:, :3] = 0.3 * r.uniform(-1, 1, (n, 3))
    cell = float(np.nextafter(np.float32(h), np.float32(1)))
    cells = int(np.ceil((0.1 + side * dx) / cell))
    grid = masav.make_grid_params((0, 0, 0), cell, (cells, cells, cells), n)
    p = masav.SphStepParams(
        grid=grid, n=n, model=model, h=h, mass=1000.0 * dx**3, rest_density=1000.0,
        sound_speed=15.0, kp=5.0, viscosity=2e-3, gravity=(0.0, -9.81, 0.0), walls=True,
        box_min=(0.05 - 0.4 * dx, 0.05 - 0.5 * dx, 0.05 - 0.6 * dx),
        box_max=(0.05 + (side - 0.4) * dx, 0.05 + (side - 0.6) * dx, 0.05 + (side - 0.5) * dx))
    order, sorted_cells, start, end = sorted_into(cpu, grid, pos)
    c = dict(p=p, n=n, pos=pos[order], vel=vel[order], cells=sorted_cells, start=start, end=end)
    _sph_cases[key] = c
    return c


def grid_args(c):
    return dict(cells=c["cells"], cell_start=c["start"], cell_end=c["end"])


def density_on(b, c, rows=False):
    n = c["n"]
    out = dict(density=np.zeros(n), pressure=np.zeros(n), stats=np.zeros(C["SPH_STAT_WORDS"], U32))
    if rows:
        out["neighbor_rows"] = np.zeros(C["SPH_ROW_MASK_WORDS"] * n, U32)
    b.sph_density(c["p"], positions=c["pos"], **grid_args(c), **out)
    return out


@case("sph_density")
def sph_density(b, cpu):
    out = {}
    for m in MODELS:
        d = density_on(b, sph_case(cpu, m))
        out[f"density {m}"], out[f"pressure {m}"] = d["density"], d["pressure"]
    return out


@case("sph_forces")
def sph_forces(b, cpu):
    out = {}
    for m in MODELS:
        c = sph_case(cpu, m)
        rows = density_on(b, c, rows=True)["neighbor_rows"]
        x = c["pos"].astype(np.float64)
        rho = 1000.0 * (1.0 + 0.05 * np.sin(97.0 * x[:, 0] + 61.0 * x[:, 1]))
        pr = 3000.0 * (1.0 + np.cos(83.0 * x[:, 2]))
        for masked in (False, True):
            accel = np.zeros((c["n"], 4))
            b.sph_forces(c["p"], positions=c["pos"], velocities=c["vel"], density=rho,
                         pressure=pr, **grid_args(c), accel=accel,
                         stats=np.zeros(C["SPH_STAT_WORDS"], U32),
                         neighbor_rows=rows if masked else None)
            v = f"{m} over row masks" if masked else m
            out[f"neighbours {v}"] = accel[:, 3].copy()
            out[f"accel {v}"] = xyz(accel)
    return out


@case("sph_integrate")
def sph_integrate(b, cpu):
    c = sph_case(cpu, "wcsph")
    n, r = c["n"], rng(13)
    acc = (60 * r.random((n, 4)) - 30).astype(np.float32)
    vk = ((60 * r.random((n, 4)) - 30) / 10).astype(np.float32)
    sums = (60 * r.random((n, 4)) - 30).astype(np.float32)
    acc[:, 3] = vk[:, 3] = sums[:, 3] = 0
    out = {}
    for op in range(10):  # euler .. drift (SphStageOp)
        xo, vo, sx, sv = (np.zeros((n, 4)) for _ in range(4))
        sx[:], sv[:] = sums, sums
        p = masav.SphIntegrateParams(n=n, op=masav.SphStageOp(op), dt=2e-3, walls=True,
                                     box_min=c["p"].box_min, box_max=c["p"].box_max,
                                     restitution=0.4, tangential_damping=0.1)
        b.sph_integrate(p, x0=c["pos"], v0=c["vel"], vk=vk if 3 <= op <= 5 else None,
                        accel=acc, x_out=xo, v_out=vo, sum_x=sx, sum_v=sv,
                        stats=np.zeros(C["SPH_STAT_WORDS"], U32))
        out[f"v op {op}"] = xyz(vo)
        if op not in (7, 8):  # kick and accelerate keep the positions
            out[f"x op {op}"] = xyz(xo)
        if 2 <= op <= 4:
            out[f"sum_v op {op}"] = xyz(sv)
    return out


# ---- DFSPH: the dfsph case with sph_density's density and masks on each backend ---------------
def field(pos, scale, amplitude, phase):
    x = pos.astype(np.float64)
    return scale * (1.0 + amplitude * np.sin(97.0 * x[:, 0] + 61.0 * x[:, 1] + 83.0 * x[:, 2] + phase))


def factor_scale(p):
    grad = p.mass * 45.0 / (np.pi * p.h**4) / 4.0
    return 1.0 / (30.0 * grad * grad)


@case("dfsph_factor")
def dfsph_factor(b, cpu):
    c = sph_case(cpu, "dfsph")
    rows = density_on(b, c, rows=True)["neighbor_rows"]
    out = {}
    for masked in (False, True):
        factor = np.zeros(c["n"])
        b.dfsph_factor(masav.DfsphParams(step=c["p"]), positions=c["pos"], **grid_args(c),
                       factor=factor, stats=np.zeros(C["SPH_STAT_WORDS"], U32),
                       neighbor_rows=rows if masked else None)
        out["factor over row masks" if masked else "factor"] = factor
    return out


@case("dfsph_rate")
def dfsph_rate(b, cpu):
    c = sph_case(cpu, "dfsph")
    rows = density_on(b, c, rows=True)["neighbor_rows"]
    f0 = factor_scale(c["p"])
    out = {}
    for solve in ("density", "divergence"):
        for masked in (False, True):
            kappa, kappa_sum = np.zeros(c["n"]), field(c["pos"], 1e-4, 0.5, 2.0)
            residual = np.zeros(C["DFSPH_RESIDUAL_WORDS"], U32)
            p = masav.DfsphParams(step=c["p"], solve=solve, dt=1e-3, slot=3, first=True,
                                  warm_scale=0.5, min_neighbors=20)
            b.dfsph_rate(p, positions=c["pos"], velocities=c["vel"],
                         density=field(c["pos"], 1000.0, 0.02, 0.0),
                         factor=field(c["pos"], f0, 0.2, 1.0), **grid_args(c), kappa=kappa,
                         kappa_sum=kappa_sum, residual=residual,
                         neighbor_rows=rows if masked else None)
            v = solve + (" over row masks" if masked else "")
            out[f"kappa {v}"], out[f"kappa sum {v}"] = kappa, kappa_sum
            out[f"residual {v}"] = np.array([float(int(residual[7]) << 32 | int(residual[6]))])
    return out


@case("dfsph_correct")
def dfsph_correct(b, cpu):
    c = sph_case(cpu, "dfsph")
    rows = density_on(b, c, rows=True)["neighbor_rows"]
    out = {}
    for first in (False, True):
        for masked in (False, True):
            v0 = c["vel"].astype(np.float64)
            v1 = v0.copy()
            p = masav.DfsphParams(step=c["p"], solve="density", dt=1e-3, slot=0, first=first,
                                  warm_scale=0.5, min_neighbors=0)
            b.dfsph_correct(p, positions=c["pos"], kappa=field(c["pos"], 1e-4, 0.5, 0.5),
                            **grid_args(c), velocities=v1,
                            stats=np.zeros(C["SPH_STAT_WORDS"], U32),
                            neighbor_rows=rows if masked else None)
            name = "dv" + (" warm start" if first else "") + (" over row masks" if masked else "")
            out[name] = xyz(v1 - v0)
    return out


# ---- the electron cloud, its light and volume -------------------------------------------------
_cloud = {}


def cloud(cpu):
    """A small lit cloud of the atom scene's default state, made on the CPU backend."""
    if not _cloud:
        state = masav.default_scene("atom")["atom.state"]
        a = masav.Atom(cpu, state=state, particles=6000, density_dims=24, volume_dims=20,
                       photons=256, use_cache=False)
        a.build_cloud()
        a.build_density()
        a.build_table()
        a.illuminate()
        _cloud.update(atom=a, state=state, positions=a.positions, density=a.density,
                      phase=a.phase, illumination=a.illumination)
    return _cloud


@case("orbital_sample")
def orbital_sample(b, cpu):
    ci = masav.check_inputs("orbital_sample")
    state = masav.default_scene("atom")["atom.state"]
    p, tables = masav.orbital_tables(state, count=ci["points"], seed=ci["seed"])
    pos = np.zeros((p.count, 4))
    b.orbital_sample(p, tables, pos)
    return {"positions xyz": xyz(pos)}


@case("cloud_density")
def cloud_density(b, cpu):
    pos = cloud(cpu)["positions"].astype(np.float32)
    g = cloud(cpu)["atom"].density_grid
    _, _, start, end = sorted_into(cpu, g, pos)
    density = np.zeros(masav.grid_cell_count(g))
    b.cloud_density(masav.CloudDensityParams(grid=g, particles=len(pos)), start, end, density)
    return {"density": density}


@case("scatter_table")
def scatter_table(b, cpu):
    p = masav.ScatterTableParams(rows=6, first_row=100, photons_per_row=2048, seed=3)
    entries = p.rows * (p.bins + C["SCATTER_EXTRAS"])
    table, hits = np.zeros(entries), np.zeros(entries, U32)
    b.scatter_table(p, table, hits)
    return {"photon hits": hits}


@case("nebula_illuminate")
def nebula_illuminate(b, cpu):
    c = cloud(cpu)
    out = np.zeros(len(c["positions"]))
    b.nebula_illuminate(c["atom"].light_params, c["positions"], c["density"], out)
    return {"illumination": out}


@case("nebula_view")
def nebula_view(b, cpu):
    c = cloud(cpu)
    light = np.zeros(len(c["positions"]))
    b.nebula_view(c["atom"].light_params, c["positions"], c["density"], c["phase"],
                  c["illumination"], light)
    return {"light": light}


@case("voxelize")
def voxelize(b, cpu):
    c = cloud(cpu)
    n = len(c["positions"])
    g = c["atom"].volume_grid
    cells = masav.grid_cell_count(g)
    lit = 0.5 + 0.5 * np.sin(0.37 * np.arange(n))
    prob, mean, sample = np.zeros(cells), np.zeros(cells), np.zeros(cells)
    b.voxelize(masav.VoxelizeParams(grid=g, s=0.6, t=0.4, light_to_unit=1.5), c["positions"],
               lit, prob, mean, sample)
    return {"p": prob, "g": mean, "sample": sample}


def check_volume():
    """A smooth 20 x 18 x 16 field in [0, 1] over a box centred on the origin."""
    z, y, x = np.meshgrid(*(np.linspace(-1, 1, d) for d in (16, 18, 20)), indexing="ij")
    v = 0.5 + 0.5 * np.sin(3 * x) * np.cos(2 * y) * np.exp(-z * z)
    desc = masav.make_volume_desc((20, 18, 16), (-1, -0.9, -0.8), (1, 0.9, 0.8), 0.0, 1.0)
    return v.ravel(), desc


def bricks_of(b, volume, desc, tf, brick=4):
    d = desc.dims
    count = int(np.prod([-(-d[i] // brick) for i in range(3)]))
    bricks = np.zeros((count, 4))
    b.volume_bricks(masav.VolumeBrickParams(volume=desc, brick=brick, tf_size=len(tf)), volume,
                    tf, bricks)
    return bricks


@case("volume_bricks")
def volume_bricks(b, cpu):
    volume, desc = check_volume()
    return {"bricks": bricks_of(b, volume, desc, masav.transfer_function()).ravel()}


@case("volume_brick_skip")
def volume_brick_skip(b, cpu):
    bx, by, bz = 23, 17, 11
    n = bx * by * bz
    i = np.arange(n)
    x, y, z = i % bx - 8.0, i // bx % by - 9.0, i // (bx * by) - 5.0
    scattered = rng(5).random(n) < 6 / 256
    alpha = np.zeros((n, 4))
    alpha[:, 1] = alpha[:, 3] = 1.0
    alpha[:, 2] = np.where((x * x + y * y + z * z < 20) | scattered, 0.5, 0.0)
    distances = np.zeros(2 * n, U32)
    for axis in range(3):
        b.volume_brick_skip(masav.BrickSkipParams(bricks=(bx, by, bz), axis=axis, radius=6), alpha,
                            distances)
    return {"strides": alpha[:, 3].astype(U32)}


@case("raymarch")
def raymarch(b, cpu):
    volume, desc = check_volume()
    tf = masav.transfer_function()
    bricks = bricks_of(cpu, volume, desc, tf)  # identical inputs: the CPU's bricks
    rp = masav.RaymarchParams(volume=desc, width=48, height=36, eye=(1.2, -2.6, 1.5),
                              up=(0, 0, 1), step=0.05, reference_step=0.1, brick=4,
                              tf_size=len(tf))
    out = {}
    for name, clip, shade in (("image", False, False), ("image clipped and shaded", True, True)):
        rp.clip = masav.Clip(enabled=clip, axis=0, position=0.45, keep_above=True)
        rp.shading = masav.Shading(enabled=shade)
        image = np.zeros((48 * 36, 4))
        b.raymarch(rp, volume, tf, bricks, image)
        out[name] = image.ravel()
    return out
