#!/usr/bin/env bash
# Installs everything gpugeom needs on a fresh Debian 12 machine (run as root).
# Idempotent: packages already present are skipped quickly.
set -euo pipefail
APT_PKGS=(cmake g++ make ninja-build ccache clang libomp-dev libgtest-dev googletest
          libpng-dev zlib1g-dev libcgal-dev libgmp-dev libmpfr-dev libbenchmark-dev libtbb-dev
          clang-format pkg-config)
# The documentation (scripts/docs.sh): Doxygen reads the headers for the C++ reference.
[ "${DOCS_DEPS:-1}" = 1 ] && APT_PKGS+=(doxygen)
missing=()
for p in "${APT_PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[install_deps] apt-get install ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# Python side: the package's build tools (nanobind, scikit-build-core), its tests (pytest) and
# the oracles and plotting used by tests, examples and benchmarks, and meshio (files of another
# tool, for the I/O tests).
PY=${PYTHON:-python3}
if ! "$PY" -c "import numpy, scipy, matplotlib, nanobind, scikit_build_core, pytest, meshio" >/dev/null 2>&1; then
  echo "[install_deps] pip install numpy scipy matplotlib nanobind scikit-build-core pytest meshio"
  "$PY" -m pip install -q numpy scipy matplotlib "nanobind>=2.0" "scikit-build-core>=0.10" pytest meshio
fi
# gpugeom.dask (distributed triangulations) and its tests: Dask and its distributed scheduler.
if ! "$PY" -c "import dask.array, distributed" >/dev/null 2>&1; then
  echo "[install_deps] pip install dask[array] distributed"
  "$PY" -m pip install -q "dask[array]" distributed
fi
# The documentation site (scripts/docs.sh): Sphinx with Markdown pages, the gallery, the C++
# reference through Breathe and the Furo theme.
if [ "${DOCS_DEPS:-1}" = 1 ] && ! "$PY" -c "import sphinx, myst_parser, sphinx_gallery, breathe, furo" >/dev/null 2>&1; then
  echo "[install_deps] pip install sphinx myst-parser sphinx-gallery breathe furo"
  "$PY" -m pip install -q "sphinx>=7" "myst-parser>=3" "sphinx-gallery>=0.16" "breathe>=4.35" furo
fi
# Benchmark-only anchor (Shewchuk's Triangle): optional, the tests never need it.
if ! "$PY" -c "import triangle" >/dev/null 2>&1; then
  "$PY" -m pip install -q triangle >/dev/null 2>&1 || echo "[install_deps] note: the 'triangle' package (a benchmark anchor) could not be installed"
fi
# Test and benchmark oracle for the Voronoi cells (freud, periodic cells on all host cores):
# optional, the test that compares with it is skipped without it.
if ! "$PY" -c "import freud" >/dev/null 2>&1; then
  "$PY" -m pip install -q freud-analysis >/dev/null 2>&1 || echo "[install_deps] note: the 'freud-analysis' package (an oracle for the Voronoi cells) could not be installed"
fi
echo "[install_deps] done"
