#!/usr/bin/env bash
# Runs on the lent GPU machine (from the repository root, .devbin/ carried): GPU tests, then
# compute-sanitizer over them, then the benchmarks; a short table last. Logs go to $OUT.
set -u
export LD_LIBRARY_PATH=$PWD/.devbin/lib:${LD_LIBRARY_PATH:-}
OUT=${OUT:-/tmp/gg_out}
mkdir -p "$OUT"
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee "$OUT/gpu.txt"
[ -x .devbin/gpugeom ] && .devbin/gpugeom info --device
status=0
TESTS=${TESTS:-test_*_cuda}  # a glob: which GPU test binaries to run (and sanitise); none: skip
if [ "$TESTS" != none ]; then
echo "== GPU tests (label gpu)"
# (3D Delaunay's suite checks every size against the CPU executor and the exact checker on the
# host: uncapped it takes more than a 600 s call on the H200 host, 73 s at 2*10^4)
export GG_DEL3D_MAX_N=${GG_DEL3D_MAX_N:-50000}
for t in .devbin/$TESTS; do
  "$t" --gtest_brief=1 >"$OUT/$(basename "$t").log" 2>&1
  rc=$?
  echo "$(basename "$t"): rc=$rc $(grep -E '^\[  (PASSED|FAILED)' "$OUT/$(basename "$t").log" | tr '\n' ' ')"
  [ $rc -ne 0 ] && { status=1; tail -30 "$OUT/$(basename "$t").log"; }
done
if [ "${SKIP_SANITIZER:-0}" != 1 ]; then
  echo "== compute-sanitizer memcheck"
  CS=$(command -v compute-sanitizer || echo /usr/local/cuda/bin/compute-sanitizer)
  for t in .devbin/$TESTS; do
    GG_UNDER_SANITIZER=1 GG_DEL2D_MAX_N=5000 GG_HULL3D_MAX_N=5000 GG_DEL3D_MAX_N=3000 GG_TEST_TUPLES=1500 timeout 420 "$CS" --tool memcheck --leak-check full --error-exitcode 9 "$t" --gtest_brief=1 \
      >"$OUT/memcheck_$(basename "$t").log" 2>&1
    echo "memcheck $(basename "$t"): rc=$? $(grep -E 'ERROR SUMMARY' "$OUT/memcheck_$(basename "$t").log" | tail -1)"
  done
  GG_TEST_TUPLES=1500 timeout 120 "$CS" --tool synccheck --error-exitcode 9 .devbin/test_exec_cuda --gtest_brief=1 >"$OUT/synccheck.log" 2>&1
  echo "synccheck test_exec_cuda: rc=$? $(grep -E 'ERROR SUMMARY' "$OUT/synccheck.log" | tail -1)"
fi
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = edt ]; then
  echo "== SciPy oracle through the CLI on the CUDA backend"
  GPUGEOM_BACKEND=cuda python3 tests/edt/test_scipy_oracle.py .devbin/gpugeom 2>&1 | tail -1
fi
if [ -d .devbin/py/gpugeom ] && [ "${PYTHON_SET:-1}" != 0 ]; then
  echo "== Python package: pytest (CPU and CUDA backends, CuPy / PyTorch device arrays)"
  PYTHONPATH=$PWD/.devbin/py python3 -m pytest -q -p no:cacheprovider -rs python/tests 2>&1 |
    tee "$OUT/pytest.txt" | tail -6
  [ "${PIPESTATUS[0]}" -ne 0 ] && status=1
  if [ "${PYTHON_BENCH:-1}" = 1 ]; then
    echo "== Python package benchmark (SciPy and CuPy in the same run)"
    PYTHONPATH=$PWD/.devbin/py python3 bench/python_api.py --reps 3 --csv "$OUT/python_api.csv" 2>&1 |
      tee "$OUT/python_api.txt"
    echo "== N-D distance transform against CuPy and SciPy (issue 54; SciPy takes minutes there: skipped)"
    PYTHONPATH=$PWD/.devbin/py python3 bench/edt_nd.py --reps 3 --indices --scipy-max 0 2>&1 | tee "$OUT/edt_nd.txt"
    echo "== 3D Voronoi diagram against SciPy (issue 49)"
    PYTHONPATH=$PWD/.devbin/py python3 bench/voronoi3d.py --reps 3 2>&1 | tee "$OUT/voronoi3d.txt"
    # freud's wheels come carried in .whl/ (the GPU machine has no network)
    # (--no-deps: their dependencies NumPy and friends are there already; pip would look for them in .whl)
    python3 -c "import freud" 2>/dev/null || python3 -m pip install -q --no-deps --no-index --target /tmp/gg_wheels .whl/*.whl 2>&1 | tail -1
    PYTHONPATH=$PWD/.devbin/py:/tmp/gg_wheels python3 bench/voronoi_cells.py --reps 3 2>&1 | tee "$OUT/voronoi_cells.txt"
  fi
fi
[ "${ONLY_PY:-0}" = 1 ] && exit $status
CSV="$OUT/bench.csv"
rm -f "$CSV"
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = del2d ]; then
  echo "== 2D Delaunay benchmarks (end to end, host in and out; CGAL on one core in the same run)"
  D=.devbin/gpugeom_bench_del2d
  SZ=${DEL2D_SIZES:-1e5,1e6,1e7}
  for n in 1e6 1e7; do python3 bench/terrain_contours.py -n $n -o /tmp/terrain_$n.npy; done
  # Triangle's wheel comes carried in .whl/ (the GPU machine has no network; --no-deps: pip
  # would look for NumPy there too)
  python3 -c "import triangle" 2>/dev/null || python3 -m pip install -q --no-deps --no-index --target /tmp/gg_wheels .whl/triangle-*.whl 2>&1 | tail -1
  export PYTHONPATH=/tmp/gg_wheels${PYTHONPATH:+:$PYTHONPATH}
  {
    $D --backend cuda --dists uniform,gaussian,thin_circle,circle,grid,two_segments --sizes $SZ --reps 3 --csv "$CSV"
    $D --backend cuda --files /tmp/terrain_1e6.npy,/tmp/terrain_1e7.npy --reps 3 --csv "$CSV" | tail -n +3
    if [ "${DEL2D_CPU:-1}" = 1 ]; then
      python3 bench/anchor_del2d.py --gpugeom .devbin/gpugeom --dists uniform,circle,grid --sizes 1e6 \
        --files /tmp/terrain_1e6.npy --tools triangle --csv "$CSV"
      python3 bench/anchor_del2d.py --gpugeom .devbin/gpugeom --dists uniform --sizes 1e6,1e7 --tools triangle,scipy-qhull \
        --csv "$CSV" | tail -n +2
      $D --backend cpu --dists uniform,circle,grid --sizes 1e6 --reps 3 --cgal --csv "$CSV" | tail -n +3
      $D --backend cpu --dists uniform --sizes 1e7 --reps 1 --cgal --csv "$CSV" | tail -n +3
    fi
    [ "${DEL2D_HUGE:-1e8}" != skip ] && $D --backend cuda --dists uniform --sizes ${DEL2D_HUGE:-1e8} --reps 1 --csv "$CSV" | tail -n +3
  } 2>&1 | tee "$OUT/bench_del2d.txt"
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = cdt2d ]; then
  echo "== 2D constrained Delaunay (end to end; the plain Delaunay of the same points; CGAL CDT_2 and Triangle -p on one core)"
  python3 -c "import triangle" 2>/dev/null || python3 -m pip install -q --no-deps --no-index --target /tmp/gg_wheels .whl/triangle-*.whl 2>&1 | tail -1
  export PYTHONPATH=/tmp/gg_wheels${PYTHONPATH:+:$PYTHONPATH}
  CI=/tmp/cdt_inputs
  rm -rf $CI && mkdir -p $CI
  IN=""
  for n in $(echo ${CDT_CONTOURS:-4e5,1e6,1e7} | tr , ' '); do
    python3 bench/terrain_contours.py -n $n -o /tmp/contours_$n.npy --segments /tmp/contours_${n}_segments.npy | tail -1
    IN="$IN,/tmp/contours_$n.npy:/tmp/contours_${n}_segments.npy"
  done
  PS=$(echo ${CDT_PSLG:-1e5,1e6,1e7} | tr , '\n' | sed 's/^/pslg:/' | paste -sd,)
  {
    .devbin/gpugeom_bench_cdt2d --backend cuda --inputs "$PS$IN" --reps 3 --check --check-max ${CDT_CHECK_MAX:-2e6} \
      --cgal ${CDT_CGAL_MAX:-1e7} --save $CI --csv "$CSV"
    # the outside of the segments removed, as Triangle -p does
    .devbin/gpugeom_bench_cdt2d --backend cuda --inputs "$PS$IN" --reps 3 --enclosed --csv "$CSV" | tail -n +3
    python3 bench/anchor_cdt2d.py --dir $CI --max-n ${CDT_TRIANGLE_MAX:-1e7} --csv "$CSV"
  } 2>&1 | tee "$OUT/bench_cdt2d.txt"
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = del3d ]; then
  echo "== 3D Delaunay benchmarks (end to end; CGAL Delaunay_triangulation_3 on one core)"
  .devbin/gpugeom_bench_del3d --reps ${DEL3D_REPS:-3} ${DEL3D_JOBS:-uniform:100000 uniform:1000000 ball:1000000 gaussian:1000000 thin_sphere:1000000 sphere:1000000} \
    2>&1 | tee "$OUT/bench_del3d.txt"
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = hull3d ]; then
  echo "== 3D convex hull benchmarks (end to end and on the device; CGAL and Qhull on one core)"
  H=.devbin/gpugeom_bench_hull3d
  HD=/tmp/hull_inputs
  rm -rf $HD && mkdir -p $HD
  {
    $H --backend cuda --dists ball,uniform,thin_box,thin_sphere,sphere --sizes ${HULL3D_SIZES:-1e6,1e7} --reps 3 \
      --cgal ${HULL3D_CGAL_MAX:-1e6} --save $HD --csv "$CSV"
    [ "${HULL3D_HUGE:-1e8}" != skip ] && $H --backend cuda --dists ball --sizes ${HULL3D_HUGE:-1e8} --reps 1 --csv "$CSV" | tail -n +3
    if [ "${HULL3D_SCAL:-1}" = 1 ]; then
      $H --backend cuda --dists scal:10000,scal:20000,scal:40000,scal:80000,scal:160000,scal:320000,scal:640000 \
        --sizes 1e6 --reps 3 --cgal 1e6 --save $HD --csv "$CSV" | tail -n +3
    fi
    python3 bench/anchor_hull3d.py --dir $HD --max-n ${HULL3D_QHULL_MAX:-1e6} --csv "$CSV"
  } 2>&1 | tee "$OUT/bench_hull3d.txt"
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = digital ]; then
  echo "== The digital methods (issue 20) beside the incremental ones and CGAL, in the same run"
  D=.devbin/gpugeom_bench_del2d
  for n in 1e6 1e7; do [ -f /tmp/terrain_$n.npy ] || python3 bench/terrain_contours.py -n $n -o /tmp/terrain_$n.npy; done
  {
    $D --backend cuda --dists uniform,gaussian,thin_circle --sizes ${DIGITAL_SIZES:-1e5,1e6,1e7} --reps 3 \
      --digital ${DIGITAL_GRIDS:-0,2048,4096,16384} --cgal --csv "$CSV"
    $D --backend cuda --files /tmp/terrain_1e6.npy,/tmp/terrain_1e7.npy --reps 3 --digital 0 --cgal \
      --csv "$CSV" | tail -n +3
    .devbin/gpugeom_bench_hull3d --backend cuda --dists ball,uniform,thin_box,thin_sphere,sphere \
      --sizes ${DIGITAL_HULL_SIZES:-1e6,1e7} --reps 3 --methods incremental,digital \
      --cgal ${DIGITAL_HULL_CGAL_MAX:-1e6} --csv "$CSV" | tail -n +2
    .devbin/gpugeom_bench_hull3d --backend cuda --dists scal:1000,scal:100000,scal:1000000 --sizes 1e7 \
      --reps 3 --methods incremental,digital --csv "$CSV" | tail -n +3
  } 2>&1 | tee "$OUT/bench_digital.txt"
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = edt ]; then
  echo "== EDT benchmarks (PBA on both backends, JFA, CuPy/SciPy/OpenCV anchors)"
  E=.devbin/gpugeom_bench_edt
  {
    $E --backend cuda --sides 1024,2048,4096,8192,16384 --density 0.001,0.1,0.5 --reps 5 --csv "$CSV"
    $E --backend cuda --sides 2048,8192 --density 0.1 --reps 3 --jfa --csv "$CSV" | grep jfa
    $E --backend cpu --sides 1024,4096 --density 0.1 --reps 3 --csv "$CSV" | grep -v '^edt  *grid'
    $E --backend cuda --dim 3 --sides 128,256,512 --density 0.001,0.1,0.5 --reps 5 --csv "$CSV" | grep -v '^edt  *grid'
    $E --backend cuda --dim 3 --sides 1024 --density 0.1 --reps 2 --csv "$CSV" | grep -v '^edt  *grid'
    $E --backend cpu --dim 3 --sides 256 --density 0.1 --reps 2 --csv "$CSV" | grep -v '^edt  *grid'
  } 2>&1 | tee "$OUT/bench_edt.txt"
  python3 bench/anchor_edt.py --sides 1024,2048,4096,8192,16384 --density 0.1 --tools cupy,scipy,opencv,edt --csv "$CSV" 2>&1 | tee "$OUT/anchor_edt.txt"
  python3 bench/anchor_edt.py --dim 3 --sides 128,256,512,1024 --density 0.1 --tools cupy,scipy --csv "$CSV" 2>&1 | tee -a "$OUT/anchor_edt.txt"
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = cvd ]; then
  echo "== CVD benchmarks (time per Lloyd iteration) and a stipple of a photograph"
  C=.devbin/gpugeom_bench_cvd
  {
    $C --backend cuda --sides 1024,4096,8192 --sites 1000,10000,100000,1000000 --iters 10 --csv "$CSV"
    $C --backend cpu --sides 1024,4096 --sites 1000,100000 --iters 3 --csv "$CSV" | grep -v '^cvd  grid'
    $C --backend cuda --dim 3 --sides 128,256 --sites 1000,100000 --iters 5 --csv "$CSV" | grep -v '^cvd  grid'
  } 2>&1 | tee "$OUT/bench_cvd.txt"
  # scikit-image's "camera" photograph (512^2), upscaled to 1024^2 (bilinear)
  python3 -c "import numpy as n, skimage.data as d, skimage.transform as t; n.save('/tmp/camera1024.npy', t.resize(d.camera(), (1024, 1024), order=1).astype(n.float32))" &&
  for b in cuda cpu; do
    /usr/bin/time -f "stipple end to end ($b): %e s wall" .devbin/gpugeom --backend $b --verbose stipple /tmp/camera1024.npy -n 20000 \
      -o "$OUT/camera_$b.svg" --png "$OUT/camera_$b.png" --png-scale 1 2>&1 | tr '\r' '\n' | grep -E "converged|stopped|time|wall|dots"
  done
fi
if [ "${BENCH_SET:-all}" = all ] || [ "${BENCH_SET:-all}" = foundation ]; then
  echo "== benchmarks"
  B=.devbin/gpugeom_bench
  SIZES=${BENCH_SIZES:-1000000,10000000}
  $B --problem hilbert --dist uniform,grid --sizes $SIZES --csv "$CSV" >"$OUT/bench_hilbert.txt"
  $B --problem hilbert --dim 2 --dist uniform --sizes $SIZES --csv "$CSV" >>"$OUT/bench_hilbert.txt"
  $B --problem orient3d --dist uniform,sphere,grid --sizes $SIZES --csv "$CSV" >"$OUT/bench_orient.txt"
  $B --problem insphere --dist uniform,grid --sizes $SIZES --csv "$CSV" >"$OUT/bench_insphere.txt"
  $B --problem insphere --dist sphere --sizes 100000,1000000 --csv "$CSV" >>"$OUT/bench_insphere.txt"
  if [ -x .devbin/anchor_cgal ]; then
    .devbin/anchor_cgal --problem delaunay2d --dist uniform --sizes 1000000 --csv "$CSV" >"$OUT/anchor.txt" 2>&1
    .devbin/anchor_cgal --problem hull3d --dist ball --sizes 1000000 --csv "$CSV" >>"$OUT/anchor.txt" 2>&1
    cat "$OUT/anchor.txt"
  fi
  cat "$OUT/bench_hilbert.txt" "$OUT/bench_orient.txt" "$OUT/bench_insphere.txt" | grep -v '^problem' | sort -s -k1,1 -k2,2 -k3,3n
fi
exit $status
