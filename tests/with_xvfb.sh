#!/bin/sh
# with_xvfb.sh CMD...: runs CMD where xvfb-run is installed; elsewhere says why and exits 77
# (ctest: skipped). For the tests that read what a demo run under Xvfb wrote: without xvfb-run
# that run is skipped (demo_xvfb.sh), so there is nothing for them to check.
if ! command -v xvfb-run >/dev/null; then
  echo "SKIPPED: xvfb-run is not installed, so the demo run under Xvfb that writes this test's inputs was skipped (tools/setup installs xvfb and xauth)"
  exit 77
fi
exec "$@"
