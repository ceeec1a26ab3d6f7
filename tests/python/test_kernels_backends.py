"""Every kernel of the kernel list, cpu against vulkan (lavapipe), through the Python API: the
same host inputs to both, the outputs judged by masav.compare_outputs with the kernel's C++
cross-check tolerances (bit for bit, per-output tolerances, or chi-square). A kernel without a
case here fails, so a kernel added to kernels.inc must get one."""
import pytest

import masav
from kernel_cases import CASES

KERNELS = [k[0] for k in masav.kernels()]


def test_every_kernel_has_a_case():
    assert sorted(set(KERNELS) - set(CASES)) == []
    assert sorted(set(CASES) - set(KERNELS)) == []


@pytest.mark.parametrize("kernel", KERNELS)
def test_cpu_against_vulkan(kernel, cpu, vulkan):
    if kernel not in CASES:
        pytest.fail(f"no Python case for kernel {kernel} (tests/python/kernel_cases.py)")
    want = CASES[kernel](cpu, cpu)
    got = CASES[kernel](vulkan, cpu)
    assert want.keys() == got.keys()
    v = masav.compare_outputs(kernel, got, want)
    assert v["passed"], f"{kernel}: {v['metrics']}; allowed: {v['tolerance']}"


def test_a_perturbed_output_fails_the_comparison(cpu):
    """The comparison can fail: the CPU's sort against itself with one key changed."""
    want = CASES["radix_sort"](cpu, cpu)
    got = {k: v.copy() for k, v in want.items()}
    got["values"][17] ^= 1
    v = masav.compare_outputs("radix_sort", got, want)
    assert not v["passed"] and "1 of" in v["metrics"]
