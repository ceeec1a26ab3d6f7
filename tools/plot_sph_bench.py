#!/usr/bin/python3
"""Plots of the SPH benchmarks (masav bench sph | dambreak).

usage: tools/plot_sph_bench.py OUT_PREFIX RECORD.json...
  reads the records (each names its benchmark: sph or dambreak; a later record's throughput row
  replaces an earlier one of the same backend, integrator and count, and only the last record's
  error sweep is drawn) and writes
  OUT_PREFIX_throughput.png  particle-steps/s per backend x integrator x particle count, with the
                             thesis's Table 4.1 (32,768 particles) for comparison;
  OUT_PREFIX_pareto.png      run time against error (integrator x dt against RK4 at dt0/16), the
                             Pareto front of all backends' runs drawn as a step line;
  OUT_PREFIX_dambreak.png    the simulated surge front against the laboratory measurements.
Needs python3-matplotlib (tools/setup --plots).
"""
import sys

from plot_common import groups, label_axes, load_records, plt, save

# Thesis Table 4.1: frames per second at 32,768 particles (water), Quadro FX 5800 / Core2 Duo.
THESIS_WATER_FPS = {"GPU euler": 8.8, "GPU rk4": 8.6, "CPU euler": 0.41, "CPU rk4": 0.25}


def plot_throughput(prefix, sph_records):
    latest = {}
    for rec in sph_records:
        for r in rec.get("throughput", []):
            latest[(r["backend"], r["integrator"], r["particles"])] = r
    rows = list(latest.values())
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(8, 4.8))
    for (be, integ), runs in groups(rows, "backend", "integrator"):
        pts = sorted((r["particles"], r["particle_steps_per_s"]) for r in runs)
        ax.plot(*zip(*pts), "-o", label=f"{be} {integ}")
    for name, fps in THESIS_WATER_FPS.items():
        ax.plot([32768], [fps * 32768], "k*" if name.startswith("GPU") else "kx", ms=9)
        ax.annotate(f"thesis {name}", (32768, fps * 32768), fontsize=7,
                    xytext=(6, -9 if "rk4" in name else 2),
                    textcoords="offset points")
    ax.axhline(0.75e6, color="grey", ls=":", lw=1)
    ax.annotate("SPEC §5 CPU target", (rows[0]["particles"], 0.75e6), fontsize=7, color="grey")
    label_axes(ax, "particles", "particle-steps / s", "SPH throughput (water preset)")
    save(fig, f"{prefix}_throughput.png", 120)


def pareto(points):
    """Points (time, error) not dominated by a faster and more accurate one, by time."""
    front, best = [], float("inf")
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


def plot_pareto(prefix, sph_records):
    sweeps = [rec["error_sweep"] for rec in sph_records if "error_sweep" in rec]
    if not sweeps:
        return
    sweep = sweeps[-1]
    rows = [r for r in sweep.get("rows", []) if r["stable"]]
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(8, 4.8))
    markers = {"euler": "o", "symplectic-euler": "v", "leapfrog": "s", "rk4": "D"}
    for (be, integ), runs in groups(rows, "backend", "integrator"):
        pts = sorted((r["wall_ms"], r["position_error_over_h"], r["dt_s"]) for r in runs)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-" + markers.get(integ, "o"),
                label=f"{be} {integ}", alpha=0.8)
    front = pareto([(r["wall_ms"], r["position_error_over_h"]) for r in rows])
    ax.step([p[0] for p in front], [p[1] for p in front], "k--", where="post", lw=1,
            label="Pareto front")
    label_axes(ax, "wall time, ms", "RMS position error / h",
               f"run time against error: dam break, {sweep['particles']} particles, "
               f"{sweep['time_s']:.4g} s, ref. RK4 at dt0/16", title_size=9)
    save(fig, f"{prefix}_pareto.png", 120)


def plot_dambreak(prefix, records):
    if not records:
        return
    fig, ax = plt.subplots(figsize=(7, 4.8))
    for rec in records:
        sim = rec["simulated"]
        ax.plot(sim["T"], sim["Z"], "-",
                label=f"masav {rec['pressure_model']} / {rec['integrator']}, "
                      f"{rec['particles']} particles ({rec['backend']})")
    markers = ["o", "s", "^", "v"]
    for k, exp in enumerate(records[0]["experiments"]):
        pts = exp["points"]
        ax.plot([p["T"] for p in pts], [p["Z"] for p in pts], markers[k % 4], mfc="none",
                label=f"{exp['source']} (mean |dZ| {exp.get('mean_abs_difference', 0):.3f})")
    label_axes(ax, "T = t sqrt(2 g / a)", "Z = surge front / a",
               "dam break: surge front against laboratory data", log_x=False, log_y=False)
    save(fig, f"{prefix}_dambreak.png", 120)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    prefix = sys.argv[1]
    records = load_records(sys.argv[2:])
    plot_throughput(prefix, records.get("sph", []))
    plot_pareto(prefix, records.get("sph", []))
    plot_dambreak(prefix, records.get("dambreak", []))


if __name__ == "__main__":
    main()
