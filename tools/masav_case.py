"""What the peer comparisons (tools/*-compare) share: masav's dam-break column and the lattice it
places its particles on, and the CPU a record was measured on."""
import math
import platform

A = 0.146  # masav's dam-break column width (engine/sph/sph_presets.cpp)


def dambreak_lattice(n):
    """masav's column for n particles (engine/sph/sph_particles.cpp): the spacing
    dx = (a 2a 4a / n)^(1/3), the columns in x and in masav's z, the whole layers, and the
    particles of the partial top layer."""
    dx = (A * 2 * A * 4 * A / n) ** (1.0 / 3.0)
    nx = max(1, math.floor(A / dx + 1e-6))
    nz = max(1, math.floor(4 * A / dx + 1e-6))
    return dx, nx, nz, n // (nx * nz), n % (nx * nz)


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"
