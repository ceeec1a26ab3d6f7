#!/usr/bin/env python3
"""The summary of a tools/gpu-report run: each SPEC section 5 target, measured, met or not.

    tools/gpu_report_summary.py OUT_DIR

Reads what tools/gpu-report left in OUT_DIR -- run.txt (key=value: mode, quick, machine, ...),
steps.tsv (name, status, seconds, log), bench_*.json (`masav bench ... --json`) and
verify_*.json (`masav verify ... --json`) -- and writes OUT_DIR/summary.md (markdown tables)
and OUT_DIR/summary.json. Standard library only.

A target is `met` = yes / no / not measured. A number is taken only from a run of the size the
target names (1,048,576 SPH particles, 2^24 pairs, the 1.1 M-particle states of thesis Table
2.3, ...): a --quick run measures the small targets and leaves the rest `not measured`.
"""
import glob
import json
import os
import sys

MILLION = 1e6
CLOUD_1M = 1_100_000  # thesis Table 2.3's 1.1 M states (state4: 1,124,640; state7: 1,123,632)


def fmt(x, digits=3):
    """x with `digits` significant digits, no exponent for everyday magnitudes."""
    if x is None:
        return "-"
    if x == 0:
        return "0"
    a = abs(x)
    if a >= 1e7 or a < 1e-3:
        return f"{x:.{digits - 1}e}"
    s = f"{x:.{digits}g}"
    if "e" in s:  # e.g. 1.23e+03 for 1234 at 3 digits
        s = f"{x:.0f}"
    return s


def load_run(out):
    run = {}
    path = os.path.join(out, "run.txt")
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                if "=" in line:
                    k, v = line.rstrip("\n").split("=", 1)
                    run[k] = v
    return run


def load_steps(out):
    steps = []
    path = os.path.join(out, "steps.tsv")
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                parts = line.rstrip("\n").split("\t")
                if len(parts) >= 3:
                    steps.append({"step": parts[0], "status": parts[1], "seconds": int(parts[2]),
                                  "log": parts[3] if len(parts) > 3 else ""})
    return steps


def load_json(out, pattern):
    records = []
    for path in sorted(glob.glob(os.path.join(out, pattern))):
        try:
            with open(path, encoding="utf-8") as f:
                records.append((os.path.basename(path), json.load(f)))
        except (OSError, ValueError) as e:
            print(f"gpu_report_summary: skipping {path}: {e}", file=sys.stderr)
    return records


# The SPH runs with a tuning option switched from the backend's default: CUDA graphs on
# (--tune cuda.graphs=on), Vulkan replays off (vulkan.replay=off), sph_forces with the wall
# images inside its walk (vulkan.sph_images_after=off, cuda.sph_images_after=off), sph_forces
# without the neighbour state (sph.neighbor_state=off); and, in records made before RK4's reach
# masks were settled, RK4 without them.
VARIANT_RUNS = ("bench_sph_graphs", "bench_sph_noreplay", "bench_sph_noreach",
                "bench_sph_imagesinside", "bench_sph_nostate")


def variant_row(f):
    """A row of a variant run (VARIANT_RUNS): compared with the default run in its own table,
    never counted as the backend's throughput."""
    return os.path.basename(f).startswith(VARIANT_RUNS)


def variant_name(f, r):
    if os.path.basename(f).startswith("bench_sph_noreach"):
        return "no reach masks"
    if os.path.basename(f).startswith("bench_sph_imagesinside"):
        return "wall images inside the walk"
    if os.path.basename(f).startswith("bench_sph_nostate"):
        return "no neighbour state"
    graphs = (r.get("per_step", {}).get("graphs") or 0) > 0
    if r.get("backend") == "cuda":
        return "CUDA graphs" if graphs else "launches"
    return "replays" if graphs else "no replays"


class Bench:
    """Every benchmark row, by kind, with the file it came from."""

    def __init__(self, records):
        self.records = records

    def of(self, kind):
        return [(f, d) for f, d in self.records if d.get("benchmark") == kind]

    def sph(self, backend, integrator, particles):
        found = None
        for f, d in self.of("sph"):
            for r in d.get("throughput", []):
                if (r.get("backend") == backend and r.get("integrator") == integrator
                        and r.get("particles") == particles and not variant_row(f)):
                    found = (f, r)
        return found

    def sort(self, backend, n, key_bits=None, impl="ours"):
        found = None
        for f, d in self.of("sort"):
            if d.get("n") != n or (key_bits is not None and d.get("key_bits") != key_bits):
                continue
            for r in d.get("rows", []):
                want = "cpu-ref" if backend == "cpu" else impl
                if r.get("backend") == backend and r.get("impl") == want:
                    found = (f, dict(r, key_bits=d.get("key_bits"), n=d.get("n")))
        return found

    def scatter(self, backend):
        found = None
        for f, d in self.of("scatter"):
            for r in d.get("rows_by_backend", []):
                if r.get("backend") == backend:
                    found = (f, dict(r, photons_per_row=d.get("photons_per_row")))
        return found

    def big_cloud_rows(self, kind, backend):
        """The rows of thesis Table 2.3's 1.1 M-particle states (bench atom / light)."""
        found = None
        for f, d in self.of(kind):
            rows = [r for r in d.get("rows", [])
                    if r.get("backend") == backend and r.get("particles", 0) >= CLOUD_1M]
            if rows:
                found = (f, rows)
        return found

    def raymarch(self, backend, volume, width, height, skip=True):
        found = None
        for f, d in self.of("raymarch"):
            for r in d.get("rows", []):
                if (r.get("backend") == backend and r.get("volume") == volume
                        and r.get("width") == width and r.get("height") == height
                        and r.get("skip_empty") == skip):
                    found = (f, r)
        return found


def target(name, backend, measured, value, threshold, met, source, note=""):
    return {"target": name, "backend": backend, "measured": measured, "value": value,
            "threshold": threshold, "met": met, "source": source, "note": note}


def not_measured(name, backend, why, threshold=None):
    return target(name, backend, why, None, threshold, "not measured", "")


def at_most(name, backend, found, pick, limit, describe):
    """A target `value <= limit` from the row `found` (file, row); `pick` gives the value."""
    if not found:
        return None
    f, r = found
    v = pick(r)
    return target(name, backend, describe(v, r), v, limit, "yes" if v <= limit else "no", f)


def at_least(name, backend, found, pick, limit, describe):
    if not found:
        return None
    f, r = found
    v = pick(r)
    return target(name, backend, describe(v, r), v, limit, "yes" if v >= limit else "no", f)


def skipped_reason(run, key, default):
    return run.get(key) or default


def gpu_targets(bench, run, backends):
    quick_note = ("not run at this size (--quick)" if run.get("quick") == "1"
                  else "no result (its bench step failed or did not run; see Steps)")
    rows = []
    for b in ("cuda", "vulkan"):
        if b not in backends:
            why = f"no {b} backend (the reason is above the table)"
            for name in ("SPH 1,048,576 particles: symplectic (leapfrog) step <= 1 ms",
                         "SPH 1,048,576 particles: RK4 step <= 4 ms",
                         "SPH 32,768 particles: RK4 >= 2,000 steps/s",
                         "radix sort 2^24 pairs >= 8 G pairs/s",
                         "scattering table >= 5e9 events/s",
                         "nebula lighting, 1.1 M particles <= 5 ms",
                         "cloud creation, 1.1 M particles <= 10 ms",
                         "raymarch 60^3 at 1024^2 >= 1,000 frames/s",
                         "raymarch 256^3 at 1920x1080 >= 200 frames/s"):
                rows.append(not_measured(name, b, why))
            continue

        def sph_ms(v, r):
            return (f"{fmt(v)} ms/step ({fmt(r['particle_steps_per_s'] / 1e9)} G particle-steps/s, "
                    f"{r['timed_steps']} steps)")

        name = "SPH 1,048,576 particles: symplectic (leapfrog) step <= 1 ms"
        rows.append(at_most(name, b, bench.sph(b, "leapfrog", 1048576),
                            lambda r: r["device_ms_per_step"], 1.0, sph_ms)
                    or not_measured(name, b, quick_note, 1.0))
        name = "SPH 1,048,576 particles: RK4 step <= 4 ms"
        rows.append(at_most(name, b, bench.sph(b, "rk4", 1048576),
                            lambda r: r["device_ms_per_step"], 4.0, sph_ms)
                    or not_measured(name, b, quick_note, 4.0))
        name = "SPH 32,768 particles: RK4 >= 2,000 steps/s"
        rows.append(at_least(name, b, bench.sph(b, "rk4", 32768), lambda r: r["steps_per_s"],
                             2000.0,
                             lambda v, r: f"{fmt(v)} steps/s ({fmt(r['device_ms_per_step'])} ms/step)")
                    or not_measured(name, b, quick_note, 2000.0))

        name = "radix sort 2^24 pairs >= 8 G pairs/s"
        # SPEC: "sorting only the key bits in use": 2^24 distinct keys need 24 bits.
        found = bench.sort(b, 1 << 24, 24) or bench.sort(b, 1 << 24)
        extra = ""
        if found and b == "cuda":
            cub = bench.sort(b, 1 << 24, found[1]["key_bits"], impl="cub")
            if cub:
                extra = f"; CUB {fmt(cub[1]['pairs_per_s'] / 1e9)} G/s"
        rows.append(at_least(name, b, found, lambda r: r["pairs_per_s"] / 1e9, 8.0,
                             lambda v, r: (f"{fmt(v)} G pairs/s ({r['key_bits']}-bit keys, "
                                           f"{fmt(r['median_ms'])} ms){extra}"))
                    or not_measured(name, b, quick_note, 8.0))

        name = "scattering table >= 5e9 events/s"
        rows.append(at_least(name, b, bench.scatter(b), lambda r: r["events_per_s"], 5e9,
                             lambda v, r: (f"{fmt(v)} events/s ({r['photons_per_row']} photons "
                                           f"per row, {fmt(r['median_ms'])} ms)"))
                    or not_measured(name, b, quick_note, 5e9))

        def worst(key):
            return lambda rs: max(rs, key=lambda r: r[key])

        name = "nebula lighting, 1.1 M particles <= 5 ms"
        found = bench.big_cloud_rows("light", b)
        if found:
            r = worst("total_ms")(found[1])
            rows.append(at_most(name, b, (found[0], r), lambda r: r["total_ms"], 5.0,
                                lambda v, r: (f"{fmt(v)} ms ({r['state']}, {r['particles']:,} "
                                              f"particles; illuminate {fmt(r['illuminate_ms'])} "
                                              f"+ view {fmt(r['view_ms'])})")))
        else:
            rows.append(not_measured(name, b, quick_note, 5.0))
        name = "cloud creation, 1.1 M particles <= 10 ms"
        found = bench.big_cloud_rows("atom", b)
        if found:
            r = worst("median_ms")(found[1])
            rows.append(at_most(name, b, (found[0], r), lambda r: r["median_ms"], 10.0,
                                lambda v, r: f"{fmt(v)} ms ({r['state']}, {r['particles']:,} particles)"))
        else:
            rows.append(not_measured(name, b, quick_note, 10.0))

        def fps(v, r):
            return f"{fmt(v)} frames/s ({fmt(r['median_ms'])} ms)"

        name = "raymarch 60^3 at 1024^2 >= 1,000 frames/s"
        rows.append(at_least(name, b, bench.raymarch(b, "60^3", 1024, 1024),
                             lambda r: 1e3 / r["median_ms"], 1000.0, fps)
                    or not_measured(name, b, quick_note, 1000.0))
        name = "raymarch 256^3 at 1920x1080 >= 200 frames/s"
        rows.append(at_least(name, b, bench.raymarch(b, "256^3", 1920, 1080),
                             lambda r: 1e3 / r["median_ms"], 200.0, fps)
                    or not_measured(name, b, quick_note, 200.0))
    return rows


def paired_times(bench, kind, backend):
    """{case: (time_ms, file)} of one backend in one benchmark kind: every kernel time that the
    same case on another backend can be compared with."""
    out = {}
    for f, d in bench.of(kind):
        if kind == "sort":
            for r in d.get("rows", []):
                if r.get("backend") == backend and r.get("impl") in ("ours", "cpu-ref"):
                    out[f"2^{d['n'].bit_length() - 1} pairs, {d['key_bits']}-bit"] = (r["median_ms"], f)
        elif kind == "grid":
            for r in d.get("rows", []):
                if r.get("backend") == backend:
                    build = "" if r.get("build", "radix") == "radix" else f" ({r['build']})"
                    for stage, ms in r.get("median_ms", {}).items():
                        out[f"{d['n']} points, {stage}{build}"] = (ms, f)
        elif kind == "atom":
            for r in d.get("rows", []):
                if r.get("backend") == backend:
                    out[f"{r['state']} ({r['particles']})"] = (r["median_ms"], f)
        elif kind == "light":
            for r in d.get("rows", []):
                if r.get("backend") == backend:
                    out[f"{r['state']} illuminate"] = (r["illuminate_ms"], f)
                    out[f"{r['state']} view"] = (r["view_ms"], f)
        elif kind == "scatter":
            for r in d.get("rows_by_backend", []):
                if r.get("backend") == backend:
                    out[f"{d['photons_per_row']} photons/row"] = (r["median_ms"], f)
        elif kind == "raymarch":
            for r in d.get("rows", []):
                if r.get("backend") == backend:
                    skip = "" if r.get("skip_empty") else " no skipping"
                    out[f"{r['volume']} at {r['width']}x{r['height']}{skip}"] = (r["median_ms"], f)
        elif kind == "sph":
            # The small systems' steps are latency, not throughput: not what the rule compares.
            for r in d.get("throughput", []):
                if r.get("backend") == backend and not variant_row(f) and r["particles"] >= 32768:
                    case = f"{r['particles']} {r['integrator']}"
                    for stage, ms in r.get("stage_ms_per_step", {}).items():
                        out[f"{case} {stage}"] = (ms, f)
                    out[f"{case} step"] = (r["device_ms_per_step"], f)
    return out


def vulkan_vs_cuda(bench, backends):
    rows = []
    name = "Vulkan within 1.5x of CUDA"
    for kind in ("sort", "grid", "atom", "scatter", "light", "raymarch", "sph"):
        label = f"{name}: {kind}"
        if not {"cuda", "vulkan"} <= set(backends):
            rows.append(not_measured(label, "vulkan/cuda", "needs both backends on the GPU", 1.5))
            continue
        vk, cu = paired_times(bench, kind, "vulkan"), paired_times(bench, kind, "cuda")
        cases = [c for c in vk if c in cu and cu[c][0] > 0]
        if not cases:
            rows.append(not_measured(label, "vulkan/cuda", "no matching runs", 1.5))
            continue
        ratios = sorted(((vk[c][0] / cu[c][0], c) for c in cases), reverse=True)
        worst, case = ratios[0]
        files = sorted({vk[case][1], cu[case][1]})
        rows.append(target(label, "vulkan/cuda",
                           f"worst {fmt(worst)}x ({case}: {fmt(vk[case][0])} vs {fmt(cu[case][0])} ms); "
                           f"{len(cases)} timings compared",
                           worst, 1.5, "yes" if worst <= 1.5 else "no", ", ".join(files)))
    return rows


def cpu_targets(bench, run):
    rows = []
    for n, ratio in ((32768, 0.6), (1048576, 0.5)):
        name = f"SPH on lavapipe >= {ratio}x the CPU backend at {n:,} particles (Euler)"
        vk, cpu = bench.sph("vulkan", "euler", n), bench.sph("cpu", "euler", n)
        if vk and cpu:
            v = vk[1]["particle_steps_per_s"] / cpu[1]["particle_steps_per_s"]
            rows.append(target(name, "vulkan/cpu",
                               f"{fmt(v)}x ({fmt(vk[1]['particle_steps_per_s'] / MILLION)} vs "
                               f"{fmt(cpu[1]['particle_steps_per_s'] / MILLION)} M particle-steps/s)",
                               v, ratio, "yes" if v >= ratio else "no",
                               ", ".join(sorted({vk[0], cpu[0]}))))
        else:
            why = "not run"
            if n == 1048576:
                why = skipped_reason(run, "sph_1m", "not run")
            rows.append(not_measured(name, "vulkan/cpu", why, ratio))
    for b, label in (("vulkan", "lavapipe"), ("cpu", "the CPU backend")):
        name = f"raymarch 60^3 at 512^2 <= 43 ms on {label} (VTK 9 fixed-point, 2 threads)"
        rows.append(at_most(name, b, bench.raymarch(b, "60^3", 512, 512), lambda r: r["median_ms"],
                            43.0, lambda v, r: f"{fmt(v)} ms ({fmt(1e3 / v)} frames/s)")
                    or not_measured(name, b, "not run", 43.0))
    name = "SPH on the CPU backend >= 5x DualSPHysics-CPU (neighbour count matched)"
    cpu = bench.sph("cpu", "euler", 32768)
    got = (f"CPU backend {fmt(cpu[1]['particle_steps_per_s'] / MILLION)} M particle-steps/s at "
           "32,768 (Euler); DualSPHysics is not run by this command") if cpu else "not run"
    rows.append(target(name, "cpu", got, None, 5.0, "not measured", cpu[0] if cpu else ""))
    return rows


def sph_table(bench):
    rows = []
    for f, d in bench.of("sph"):
        if variant_row(f):
            continue
        for r in d.get("throughput", []):
            rows.append({"backend": r["backend"], "integrator": r["integrator"],
                         "particles": r["particles"], "ms_per_step": r["device_ms_per_step"],
                         "steps_per_s": r["steps_per_s"],
                         "m_particle_steps_per_s": r["particle_steps_per_s"] / MILLION,
                         "timed_steps": r["timed_steps"],
                         # What each step asked of the device (target: no host sync per step).
                         "launches_per_step": r.get("per_step", {}).get("launches"),
                         "host_syncs_per_step": r.get("per_step", {}).get("host_syncs"),
                         "async_reads_per_step": r.get("per_step", {}).get("async_reads"),
                         "source": f})
    rows.sort(key=lambda r: (r["particles"], r["integrator"], r["backend"]))
    return rows


def graphs_table(bench):
    """Each row of a variant run (VARIANT_RUNS) against the default run of the same backend,
    integrator, particles and timed steps: wall time and host CPU per step."""
    plain, rows = {}, []
    for f, d in bench.of("sph"):
        if variant_row(f):
            continue
        for r in d.get("throughput", []):
            plain[(r["backend"], r["integrator"], r["particles"], r["timed_steps"])] = (f, r)
    for f, d in bench.of("sph"):
        if not variant_row(f):
            continue
        for r in d.get("throughput", []):
            base = plain.get((r["backend"], r["integrator"], r["particles"], r["timed_steps"]))
            row = {"backend": r["backend"], "integrator": r["integrator"],
                   "particles": r["particles"], "timed_steps": r["timed_steps"],
                   "variant": variant_name(f, r),
                   "graph_wall_ms": r["wall_ms_per_step"],
                   "graph_host_ms": r.get("per_step", {}).get("host_cpu_ms"),
                   "launch_wall_ms": None, "launch_host_ms": None, "ratio": None,
                   "source": f}
            if base:
                b = base[1]
                row.update(launch_wall_ms=b["wall_ms_per_step"],
                           launch_host_ms=b.get("per_step", {}).get("host_cpu_ms"),
                           ratio=r["wall_ms_per_step"] / b["wall_ms_per_step"],
                           source=f"{f}, {base[0]}")
            rows.append(row)
    rows.sort(key=lambda r: (r["particles"], r["integrator"], r["backend"]))
    return rows


def verify_table(records):
    rows = []
    for f, d in records:
        kernels = d.get("kernels", [])
        rows.append({"scene_file": f[len("verify_"):-len(".json")], "scene": d.get("scene"),
                     "backend": d.get("backend", {}).get("name"),
                     "reference": d.get("reference", {}).get("name"),
                     "pass": bool(d.get("pass")),
                     "kernels_passed": sum(1 for k in kernels if k.get("pass")),
                     "kernels": len(kernels),
                     "failed": [k.get("kernel") for k in kernels if not k.get("pass")],
                     "source": f})
    return rows


def dambreak_table(bench):
    rows = []
    for f, d in bench.of("dambreak"):
        for e in d.get("experiments", []):
            rows.append({"backend": d.get("backend"), "particles": d.get("particles"),
                         "source_data": e.get("source"), "points": len(e.get("points", [])),
                         "mean_abs_dz": e.get("mean_abs_difference"),
                         "max_abs_dz": e.get("max_abs_difference"), "wall_s": d.get("wall_s"),
                         "source": f})
    return rows


def md_table(title, header, rows):
    """A titled markdown table, then a blank line."""
    lines = [title, "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return lines + [""]


def markdown(run, steps, targets, sph, verify, dambreak, graphs):
    gpu = run.get("mode") == "gpu"
    lines = [f"# masav GPU report: {run.get('machine', '?')}", ""]
    if gpu:
        lines.append(f"GPU: **{run.get('gpu_name', '?')}** (compute capability "
                     f"{run.get('compute_cap') or '?'}, driver {run.get('gpu_driver') or '?'}); "
                     f"Vulkan device: {run.get('vulkan_device') or 'none'}.")
        for b, label in (("cuda", "CUDA"), ("vulkan", "Vulkan")):
            if run.get(f"why_no_{b}"):
                lines.append(f"\n**{label} not measured**: {run[f'why_no_{b}']}.")
    else:
        lines.append(f"**No NVIDIA GPU** (`nvidia-smi`: {run.get('why_no_gpu', 'absent')}): Vulkan on "
                     f"{run.get('vulkan_device') or 'no Vulkan device'} and the CPU reference on "
                     f"{run.get('host_cpu', '?')} ({run.get('cores', '?')} cores).")
    lines.append("")
    lines.append(f"- date: {run.get('date', '?')}; source tree at commit {run.get('git', '?')}; "
                 f"binary `{run.get('build_dir', '?')}/masav`: {run.get('masav_build', '?')} "
                 f"(CUDA architectures {run.get('cuda_archs', '?')})")
    lines.append(f"- backends benchmarked: {run.get('backends', '-') or '-'}; sizes: "
                 f"{'--quick (smallest; not a record)' if run.get('quick') == '1' else 'full'}"
                 f"; wall time {run.get('elapsed_s', '?')} s")
    if run.get("vk_driver_files"):
        lines.append(f"- Vulkan ICD: VK_DRIVER_FILES={run['vk_driver_files']}")
    for key in ("note_1", "note_2", "note_3", "note_4"):
        if run.get(key):
            lines.append(f"- {run[key]}")
    if gpu and "H100" not in run.get("gpu_name", ""):
        lines.append("- SPEC section 5's GPU targets are stated for one NVIDIA H100; this GPU is "
                     "compared against them as they are.")
    lines += ["", "## SPEC section 5 targets", "",
              "| target | backend | measured | met | source JSON |", "|---|---|---|---|---|"]
    for t in targets:
        lines.append(f"| {t['target']} | {t['backend']} | {t['measured']} | {t['met']} | "
                     f"{t['source'] or '-'} |")
    met = sum(1 for t in targets if t["met"] == "yes")
    missed = sum(1 for t in targets if t["met"] == "no")
    lines += ["", f"{met} met, {missed} not met, {len(targets) - met - missed} not measured.", ""]

    lines += ["## Cross-check (`masav verify`, every scene)", ""]
    if verify:
        lines += ["| scene file | backend vs reference | result | kernels | source JSON |",
                  "|---|---|---|---|---|"]
        for v in verify:
            res = "pass" if v["pass"] else "FAIL: " + ", ".join(v["failed"] or ["(see log)"])
            lines.append(f"| {v['scene_file']} | {v['backend']} vs {v['reference']} | {res} | "
                         f"{v['kernels_passed']} of {v['kernels']} | {v['source']} |")
    else:
        lines.append("No verify report was written.")
    lines.append("")

    if sph:
        lines += md_table(
            "## SPH throughput (`masav bench sph`, water preset)",
            ["particles", "integrator", "backend", "ms/step", "steps/s", "M particle-steps/s",
             "timed steps", "launches / host syncs / asynchronous reads per step", "source JSON"],
            [[f"{r['particles']:,}", r['integrator'], r['backend'], fmt(r['ms_per_step']),
              fmt(r['steps_per_s']), fmt(r['m_particle_steps_per_s']), r['timed_steps'],
              " / ".join(fmt(r[k]) for k in ("launches_per_step", "host_syncs_per_step",
                                             "async_reads_per_step")),
              r['source']] for r in sph])
    if graphs:
        lines += md_table(
            "## Captured blocks against each backend's default (CUDA graphs, "
            "`--tune cuda.graphs=on`, against launches; Vulkan without replays, "
            "`--tune vulkan.replay=off`, against replays); the forces with the wall images "
            "inside their walk (`--tune vulkan.sph_images_after=off --tune "
            "cuda.sph_images_after=off`) and the forces without the neighbour state "
            "(`--tune sph.neighbor_state=off`) against the default runs (older records: RK4 "
            "without its reach masks too)",
            ["particles", "integrator", "backend", "variant", "timed steps",
             "wall ms/step: variant", "default", "variant / default",
             "host CPU ms/step: variant", "default", "source JSON"],
            [[f"{r['particles']:,}", r['integrator'], r['backend'], r['variant'],
              r['timed_steps'],
              fmt(r['graph_wall_ms']), fmt(r['launch_wall_ms']) if r['launch_wall_ms'] else "-",
              fmt(r['ratio']) if r['ratio'] else "no run to compare",
              fmt(r['graph_host_ms']) if r['graph_host_ms'] is not None else "-",
              fmt(r['launch_host_ms']) if r['launch_host_ms'] is not None else "-",
              r['source']] for r in graphs])
    if dambreak:
        lines += md_table(
            "## Dam break against experiment (`masav bench dambreak`)",
            ["backend", "particles", "data", "points", "mean abs dZ", "max abs dZ", "wall s",
             "source JSON"],
            [[r['backend'], f"{r['particles']:,}", r['source_data'], r['points'],
              fmt(r['mean_abs_dz']), fmt(r['max_abs_dz']), fmt(r['wall_s']), r['source']]
             for r in dambreak])

    lines += ["## Steps", "", "| step | status | seconds | log |", "|---|---|---|---|"]
    for s in steps:
        lines.append(f"| {s['step']} | {s['status']} | {s['seconds']} | {s['log'] or '-'} |")
    failed = [s["step"] for s in steps if s["status"] == "FAILED"]
    lines += ["", f"{len(failed)} of {len(steps)} steps failed" +
              (": " + ", ".join(failed) if failed else "."), ""]
    return "\n".join(lines)


def write_atomic(path, text):
    """Written to a temporary name and renamed, like every file masav writes."""
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) == 2 else 2
    out = argv[1]
    run = load_run(out)
    steps = load_steps(out)
    bench = Bench(load_json(out, "bench_*.json"))
    verify = verify_table(load_json(out, "verify_*.json"))
    backends = [b for b in run.get("backends", "").split(",") if b]
    if run.get("mode") == "gpu":
        targets = gpu_targets(bench, run, backends) + vulkan_vs_cuda(bench, backends)
    else:
        targets = cpu_targets(bench, run)
    sph, dambreak, graphs = sph_table(bench), dambreak_table(bench), graphs_table(bench)
    text = markdown(run, steps, targets, sph, verify, dambreak, graphs)
    summary = {"run": run, "targets": targets, "verify": verify, "sph": sph,
               "dambreak": dambreak, "captured_blocks": graphs, "steps": steps}
    write_atomic(os.path.join(out, "summary.md"), text)
    write_atomic(os.path.join(out, "summary.json"), json.dumps(summary, indent=2) + "\n")
    print(f"wrote {os.path.join(out, 'summary.md')} and summary.json: {len(targets)} targets")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
