# tools/gpu-report (docs/GPU_REPORT.md) in its quick form, on this build: it must exit 0 and write
# summary.md with the targets of the machine it runs on. Included from tests/CMakeLists.txt, this
# file registers the test; run with -P (the test's command) it is the check itself.
#   cmake -DGPU_REPORT=tools/gpu-report -DBUILD_DIR=build -DOUT=dir -P tests/gpu_report.cmake
if(CMAKE_SCRIPT_MODE_FILE)
  file(REMOVE_RECURSE "${OUT}")
  execute_process(COMMAND "${GPU_REPORT}" --quick --skip-tests --build-dir "${BUILD_DIR}"
                          --out "${OUT}"
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "tools/gpu-report --quick exited with '${rc}' (the failed steps are "
                        "listed above; logs in ${OUT}/logs)")
  endif()
  foreach(file summary.md summary.json run.txt steps.tsv verify_sph_water.json)
    if(NOT EXISTS "${OUT}/${file}")
      message(FATAL_ERROR "tools/gpu-report --quick wrote no ${OUT}/${file}")
    endif()
  endforeach()
  file(READ "${OUT}/summary.md" summary)
  file(READ "${OUT}/run.txt" run)
  # The rows each kind of machine must show (a --quick run measures the 32,768-particle and the
  # 60^3 raymarch targets; the others may read `not measured`).
  if(run MATCHES "mode=gpu")
    set(rows
        "\\| SPH 32,768 particles: RK4 >= 2,000 steps/s \\| cuda \\| [0-9.]+ steps/s"
        "\\| raymarch 60\\^3 at 1024\\^2 >= 1,000 frames/s \\| cuda \\| [0-9.]+ frames/s"
        "\\| SPH 1,048,576 particles: symplectic \\(leapfrog\\) step <= 1 ms \\| cuda \\|"
        "\\| radix sort 2\\^24 pairs >= 8 G pairs/s \\| vulkan \\|"
        "\\| Vulkan within 1.5x of CUDA: sph \\|")
  else()
    set(rows
        "No NVIDIA GPU"
        "\\| SPH on lavapipe >= 0.6x the CPU backend at 32,768 particles \\(Euler\\) \\| vulkan/cpu \\| [0-9.]+x \\([0-9.]+ vs [0-9.]+ M particle-steps/s\\) \\| (yes|no) \\|"
        "\\| SPH on lavapipe >= 0.5x the CPU backend at 1,048,576 particles \\(Euler\\) \\| vulkan/cpu \\| skipped: --quick \\| not measured \\|"
        "\\| raymarch 60\\^3 at 512\\^2 <= 43 ms on lavapipe [^|]*\\| vulkan \\| [0-9.]+ ms [^|]*\\| (yes|no) \\| bench_raymarch_vulkan.json \\|"
        "\\| raymarch 60\\^3 at 512\\^2 <= 43 ms on the CPU backend [^|]*\\| cpu \\| [0-9.]+ ms [^|]*\\| (yes|no) \\| bench_raymarch_cpu.json \\|")
  endif()
  list(APPEND rows "\\| sph_water \\| [a-z]+ vs [a-z]+ \\| pass \\| 8 of 8 \\|" "\n0 of [0-9]+ steps failed")
  foreach(row IN LISTS rows)
    if(NOT summary MATCHES "${row}")
      message(FATAL_ERROR "${OUT}/summary.md has no row matching /${row}/:\n${summary}")
    endif()
  endforeach()
  message(STATUS "tools/gpu-report --quick: summary.md has every expected row")
  return()
endif()

if(MASAV_WITH_APP)
  # Reads the masav binary of this build; labels `tools` and `gpu-report` (the report's own
  # ctest run leaves this test out). About a minute on 2 cores without a GPU.
  add_test(NAME tools.gpu_report.quick
           COMMAND ${CMAKE_COMMAND} -DGPU_REPORT=${PROJECT_SOURCE_DIR}/tools/gpu-report
                   -DBUILD_DIR=${CMAKE_BINARY_DIR} -DOUT=${CMAKE_CURRENT_BINARY_DIR}/out/gpu_report
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(tools.gpu_report.quick PROPERTIES LABELS "tools;gpu-report"
                       ENVIRONMENT "${test_env}" TIMEOUT 600)
  # tools/gpu-pack: this build as one archive for a GPU machine without the development packages.
  add_test(NAME tools.gpu_pack
           COMMAND ${CMAKE_CURRENT_LIST_DIR}/gpu_pack.sh ${PROJECT_SOURCE_DIR}/tools/gpu-pack
                   ${CMAKE_BINARY_DIR} ${CMAKE_CURRENT_BINARY_DIR}/out/gpu_pack)
  set_tests_properties(tools.gpu_pack PROPERTIES LABELS tools ENVIRONMENT "${test_env}")
  # tools/gpu-unpack: such an archive extracted where it was built, run with its libraries.
  add_test(NAME tools.gpu_unpack
           COMMAND ${CMAKE_CURRENT_LIST_DIR}/gpu_unpack.sh ${PROJECT_SOURCE_DIR}/tools/gpu-unpack
                   ${CMAKE_CURRENT_BINARY_DIR}/out/gpu_unpack)
  set_tests_properties(tools.gpu_unpack PROPERTIES LABELS tools)
  # The summary of a GPU report (made up: no GPU here): CUDA-graph runs paired, never throughput.
  add_test(NAME tools.gpu_report_summary
           COMMAND ${CMAKE_CURRENT_LIST_DIR}/gpu_report_summary.sh
                   ${PROJECT_SOURCE_DIR}/tools/gpu_report_summary.py
                   ${CMAKE_CURRENT_BINARY_DIR}/out/gpu_report_summary)
  set_tests_properties(tools.gpu_report_summary PROPERTIES LABELS tools)
endif()
