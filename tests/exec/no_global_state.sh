#!/usr/bin/env bash
# No global mutable state in the library (issue 48): every object with static storage that the
# library's own code (namespace gpugeom) defines, read from the archive's symbol table, must be
# one of the process-wide resources below, each safe for concurrent calls and unable to change a
# result. A new global variable (a test switch, a counter) fails this test by name.
#   usage: no_global_state.sh OBJDUMP libgpugeom.a
set -euo pipefail
objdump_tool=$1
lib=$2
# Why each may exist:
allowed=(
  # thread_local scratch of the host predicates (one per calling thread)
  'gpugeom::\(anonymous namespace\)::scratch\(\)::s'
  # the names generate2d/generate3d take: built once, never changed
  'gpugeom::distributions[23]d(\[abi:cxx11\])?\(\)::v'
  # the device memory pools and the device probe, one per device, behind a mutex
  'gpugeom::\(anonymous namespace\)::pools\(\)::p'
  'gpugeom::\(anonymous namespace\)::usable\(\)::u'
  # the library's memory resource over those pools: made once, never changed
  'gpugeom::library_memory_resource\(\)::r'
  # each kernel's resident blocks per SM, an atomic memo per device
  'gpugeom::cuda_detail::resident_blocks<.*>\(.*\)::cache'
  # host staging: pinned buffers behind a mutex, copy threads, a thread_local mailbox
  'gpugeom::staging::\(anonymous namespace\)::(CopyPool::get\(\)::p|mailbox\(\)::m|pools\(\)::p)'
)
pattern=$(IFS='|'; echo "^(${allowed[*]})$")
# Objects in writable sections (.data, .bss and their thread-local forms), demangled; read-only
# constants are not state: .rodata, and .data.rel.ro, the constants that hold addresses (the
# modules' tables of entries), which the loader makes read-only once it has relocated them.
symbols=$("$objdump_tool" -t -C "$lib" 2>/dev/null |
  awk '$0 !~ /[ \t]\.data\.rel\.ro[.a-zA-Z0-9_]*[ \t]/ &&
       $0 ~ /[ \t]\.(data|bss|tdata|tbss)[.a-zA-Z0-9_]*[ \t]/ {
         sub(/^.*[ \t]\.(data|bss|tdata|tbss)[.a-zA-Z0-9_]*[ \t]+[0-9a-f]+[ \t]+/, ""); print }' |
  grep -E '^gpugeom::' | sort -u || true)
if [[ -z $symbols ]]; then
  echo "no data symbols of namespace gpugeom found in $lib: is it the library?" >&2
  exit 1
fi
bad=$(grep -vE "$pattern" <<<"$symbols" || true)
echo "$(wc -l <<<"$symbols") data symbols of namespace gpugeom in $(basename "$lib")"
if [[ -n $bad ]]; then
  echo "global state the library must not have (carry it in the options or the executor):" >&2
  echo "$bad" >&2
  exit 1
fi
echo "all of them are process-wide resources on the allowed list"
