"""masav.cross_check and cross_check_scene: the built-in checks on two backends, and the report
`masav verify` prints, word for word."""
import json
import subprocess

import pytest

import masav


def test_every_kernel_cpu_against_vulkan(cpu, vulkan):
    r = masav.cross_check("all", vulkan, cpu)
    assert r.passed, r.text
    assert len(r.rows) == len(masav.kernels())
    assert (r.backend, r.reference) == ("vulkan", "cpu")


def test_an_injected_fault_is_caught(cpu, vulkan):
    r = masav.cross_check(["radix_sort", "gather"], vulkan, cpu, inject_fault="radix_sort")
    rows = {row["kernel"]: row for row in r.rows}
    assert not rows["radix_sort"]["passed"] and rows["gather"]["passed"]
    assert r.failures == 1 and "FAIL" in r.text


def test_unknown_kernel_names_the_list(cpu):
    with pytest.raises(masav.Error, match="radix_sort"):
        masav.cross_check("radix_sorts", cpu, cpu)


def test_scene_report_is_what_masav_verify_prints(cpu, vulkan, masav_cli, source_dir, tmp_path):
    scene = str(source_dir / "scenes" / "particles.toml")
    r = masav.cross_check_scene(scene, cpu, vulkan)
    assert r.passed, r.text
    cli = subprocess.run([masav_cli, "verify", scene, "--backend", "cpu", "--reference", "vulkan",
                          "--json", str(tmp_path / "v.json")],
                         capture_output=True, text=True, check=True)
    printed = cli.stdout.split("wrote ")[0]
    assert r.text == printed
    # The saved report too, but for the wall times of each run.
    untimed = lambda text: [{k: v for k, v in row.items() if not k.startswith("ms_")}  # noqa: E731
                            for row in json.loads(text)["kernels"]]
    assert untimed((tmp_path / "v.json").read_text()) == untimed(r.json)
