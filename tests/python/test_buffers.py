"""Backends, buffers and their numpy side: round trips, the CPU backend's zero-copy views,
DLPack through numpy.from_dlpack, and the errors bad arrays get."""
import numpy as np
import pytest

import masav

KINDS = {"u32": np.uint32, "i32": np.int32, "f32": np.float32}


def test_backends_lists_cpu_and_vulkan_with_reasons():
    status = {s.name: s for s in masav.backends()}
    assert set(status) == {"cpu", "vulkan", "cuda"}
    assert status["cpu"].available and status["cpu"].devices
    for s in status.values():
        assert s.available or s.reason, f"{s.name} absent without a reason"
        assert s.name in repr(s)


def test_unknown_backend_is_a_masav_error_naming_it():
    with pytest.raises(masav.Error, match="metal"):
        masav.Backend("metal")


def test_vulkan_options_are_arguments_never_the_environment(vulkan, tmp_path, monkeypatch):
    # The module reads no variable: a loader named in the environment is not opened, the one
    # given as an argument is; the pipeline cache goes where cache_dir says, nowhere without it.
    monkeypatch.setenv("MASAV_VULKAN_LOADER", "/nonexistent/libvulkan.so.1")
    monkeypatch.setenv("MASAV_CACHE_DIR", str(tmp_path / "from_env"))
    with pytest.raises(masav.Error, match="loader could not be opened"):
        masav.Backend("vulkan", loader="/nonexistent/libvulkan.so.1")
    cached = masav.Backend("vulkan", cache_dir=str(tmp_path / "cache"))
    cached.philox_u32(masav.PhiloxParams(seed=5, stream=7), np.zeros(4 * 4096, np.uint32))
    del cached  # the pipeline cache is written when the backend closes
    assert list((tmp_path / "cache").glob("vk_pipelines_*.bin"))
    assert not (tmp_path / "from_env").exists()


def test_bad_tuning_key_names_the_allowed_ones():
    with pytest.raises(masav.Error, match="cpu.threads"):
        masav.Backend("cpu", tune={"cpu.thread": 2})
    assert "cpu.threads=2" in masav.Backend("cpu", tune=["cpu.threads=2"]).tuning


def test_error_carries_the_message_parts():
    with pytest.raises(masav.Error) as e:
        masav.Backend("cpu", device="3")
    assert "invalid device = 3" in str(e.value)
    assert e.value.problem == "invalid device = 3"
    assert e.value.remedy


@pytest.mark.parametrize("backend", ["cpu", "vulkan"])
def test_round_trip_every_kind(backend, request):
    b = request.getfixturevalue(backend)
    rng = np.random.default_rng(3)
    for kind, dtype in KINDS.items():
        a = rng.integers(0, 1 << 30, 1000).astype(dtype)
        buf = b.upload(a, kind=kind)
        assert buf.kind == kind and len(buf) == 1000
        np.testing.assert_array_equal(buf.download(), a)
    real = rng.random((500, 4)).astype(b.real_dtype)
    buf = b.upload(real)
    assert buf.kind == "real4" and buf.shape == (500, 4)
    np.testing.assert_array_equal(buf.download(), real)
    # A float width other than the backend's is converted (float32 is exact in float64).
    f32 = rng.random(300).astype(np.float32)
    got = b.upload(f32, kind="real").download()
    np.testing.assert_array_equal(got.astype(np.float32), f32)


def test_new_buffers_are_zero(cpu, vulkan):
    for b in (cpu, vulkan):
        assert not b.buffer("u32", 4096).download().any()


def test_cpu_view_is_zero_copy_and_the_next_kernel_sees_a_write(cpu):
    keys = cpu.upload(np.array([5, 3, 9, 1], dtype=np.uint32))
    view = keys.numpy()
    view[0] = 0  # written through the view, no upload
    cpu.radix_sort(masav.RadixSortParams(n=4), keys)
    np.testing.assert_array_equal(view, [0, 1, 3, 9])  # the kernel wrote into the same memory


def test_views_are_for_the_cpu_backend(vulkan):
    buf = vulkan.buffer("u32", 8)
    with pytest.raises(masav.Error, match="download"):
        buf.numpy()


def test_dlpack_shares_cpu_memory_with_numpy(cpu):
    buf = cpu.upload(np.array([4, 2, 5, 0, 1, 3], dtype=np.uint32))
    assert buf.__dlpack_device__() == (1, 0)  # kDLCPU
    shared = np.from_dlpack(buf)  # numpy marks DLPack imports read-only
    assert shared.dtype == np.uint32 and shared.shape == (6,)
    cpu.radix_sort(masav.RadixSortParams(n=6), buf)
    np.testing.assert_array_equal(shared, np.arange(6))  # the kernel's output, no copy made
    real4 = np.from_dlpack(cpu.upload(np.ones((3, 4))))
    assert real4.shape == (3, 4) and real4.dtype == np.float64
    del buf  # the array keeps the buffer alive
    np.testing.assert_array_equal(shared, np.arange(6))


def test_vulkan_buffers_do_not_pretend_to_share(vulkan):
    buf = vulkan.buffer("f32", 4)
    assert buf.__dlpack_device__()[0] == 7  # kDLVulkan
    with pytest.raises(masav.Error, match="download"):
        buf.__dlpack__()
    assert not hasattr(buf, "__cuda_array_interface__")


def test_cuda_array_interface_on_cuda(cuda):
    buf = cuda.upload(np.arange(10, dtype=np.uint32))
    cai = buf.__cuda_array_interface__
    assert cai["shape"] == (10,) and cai["typestr"] == "<u4" and cai["data"][0] != 0
    assert buf.__dlpack_device__()[0] == 2  # kDLCUDA


def sort_on(b, keys):
    b.radix_sort(masav.RadixSortParams(n=len(keys)), keys)


@pytest.mark.parametrize(
    "array, message",
    [
        (np.arange(8, dtype=np.int64), "invalid dtype = int64"),
        (np.arange(8, dtype=np.float32), "invalid dtype = float32"),
        (np.arange(16, dtype=np.uint32).reshape(4, 4), r"invalid shape = \(4, 4\)"),
        (np.arange(16, dtype=np.uint32)[::2], "not C-contiguous"),
        (np.zeros(0, dtype=np.uint32), "invalid n = 0 elements"),
    ],
)
def test_bad_arrays_are_refused_by_name(cpu, array, message):
    with pytest.raises(masav.Error, match=message) as e:
        sort_on(cpu, array)
    assert "radix_sort keys" in str(e.value)


def test_nan_and_shape_of_real4_refused(cpu):
    pos = np.zeros((10, 4))
    pos[3, 1] = np.nan
    grid = masav.make_grid_params((0, 0, 0), 0.1, (4, 4, 4), 10)
    out = np.zeros(10, dtype=np.uint32)
    with pytest.raises(masav.Error, match=r"element \(3, 1\) is nan"):
        cpu.grid_assign_cells(grid, pos, out, out.copy())
    with pytest.raises(masav.Error, match=r"invalid shape = \(10, 3\).*\(n, 4\)"):
        cpu.grid_assign_cells(grid, np.zeros((10, 3)), out, out.copy())
    with pytest.raises(masav.Error, match="writeable"):
        ro = out.copy()
        ro.flags.writeable = False
        cpu.grid_assign_cells(grid, np.zeros((10, 4)), ro, out.copy())


def test_missing_buffer_and_wrong_object(cpu):
    with pytest.raises(masav.Error, match="invalid keys = None"):
        cpu.radix_sort(masav.RadixSortParams(n=4))
    with pytest.raises(masav.Error, match="invalid keys = list"):
        cpu.radix_sort(masav.RadixSortParams(n=4), [1, 2, 3, 4])
    with pytest.raises(masav.Error, match="element type"):
        cpu.radix_sort(masav.RadixSortParams(n=4), cpu.buffer("f32", 4))


def test_contract_errors_come_through_with_their_message(cpu):
    keys = np.arange(4, dtype=np.uint32)
    with pytest.raises(masav.Error, match="radix_sort"):
        cpu.radix_sort(masav.RadixSortParams(n=5), keys)  # n past the buffer
    with pytest.raises(masav.Error, match="count = 0"):
        cpu.buffer("u32", 0)


def test_params_keywords_enums_and_errors():
    p = masav.RadixSortParams(n=7, key_bits=12, impl="portable")
    assert (p.n, p.key_bits, p.impl) == (7, 12, masav.SortImpl.portable)
    assert "key_bits=12" in repr(p)
    with pytest.raises(masav.Error, match="one of n, key_bits, impl"):
        masav.RadixSortParams(bits=3)
    with pytest.raises(masav.Error, match="impl"):
        masav.RadixSortParams(impl="fast")
    with pytest.raises(masav.Error, match="invalid n = 'x'"):
        masav.RadixSortParams(n="x")
    g = masav.make_grid_params((0, 0, 0), 0.5, (2, 3, 4), 10)
    assert g.dims == (2, 3, 4) and g.inv_cell == 2.0
    assert masav.grid_cell_count(g) == 24


def test_kernel_list_matches_the_methods():
    names = [k[0] for k in masav.kernels()]
    assert "radix_sort" in names and "raymarch" in names
    for name, params, buffers in masav.kernels():
        assert hasattr(masav.Backend, name)
        assert hasattr(masav, params)
        assert buffers
