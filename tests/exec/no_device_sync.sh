#!/usr/bin/env bash
# The library never waits for the whole device and never frees on the legacy default stream
# (issue 48): every wait is for the call's own stream, and device memory comes and goes
# stream-ordered through the call's memory resource (gpugeom/memory.hpp). A
# cudaDeviceSynchronize, a cudaStreamLegacy, or a synchronous cudaMalloc / cudaFree in the
# library's sources fails this test by file and line. (Pinned host memory, cudaMallocHost and
# cudaFreeHost, is not device memory and may stay.)
#   usage: no_device_sync.sh SOURCE_DIR...
set -euo pipefail
pattern='\bcuda(DeviceSynchronize|StreamLegacy|ThreadSynchronize|Malloc|Free|MallocManaged|MallocPitch|Malloc3D)\b'
found=$(grep -rnE --include='*.cu' --include='*.cuh' --include='*.cpp' --include='*.hpp' \
  --include='*.inl' --include='*.h' "$pattern" "$@" || true)
echo "searched $(find "$@" -type f \( -name '*.cu' -o -name '*.cuh' -o -name '*.cpp' -o \
  -name '*.hpp' -o -name '*.inl' -o -name '*.h' \) | wc -l) source files"
if [[ -n $found ]]; then
  echo "device-wide waits or unordered device allocations the library must not make" \
    "(wait for the call's stream; allocate through the executor):" >&2
  echo "$found" >&2
  exit 1
fi
echo "no cudaDeviceSynchronize, cudaStreamLegacy, cudaMalloc or cudaFree"
