# Builds the fuzzers with clang and runs each reader's target for RUNS inputs over its seeds.
# Skips (and says so) when clang is not installed.
find_program(CLANGXX clang++)
if(NOT CLANGXX)
  message("SKIP: clang++ not found; the fuzzers were not built")
  return()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -DCMAKE_CXX_COMPILER=${CLANGXX}
                -DCMAKE_BUILD_TYPE=RelWithDebInfo RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "fuzzer configure failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} -j 2 RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "fuzzer build failed")
endif()
file(GLOB seeds RELATIVE ${SOURCE_DIR}/corpus ${SOURCE_DIR}/corpus/*)
foreach(reader ${seeds})
  file(MAKE_DIRECTORY ${WORK_DIR}/corpus_${reader})
  execute_process(COMMAND ${WORK_DIR}/fuzz_${reader} -runs=${RUNS} -max_len=4096 -rss_limit_mb=2048
                          -malloc_limit_mb=1024 -seed=1 -artifact_prefix=${WORK_DIR}/ ${WORK_DIR}/corpus_${reader} ${SOURCE_DIR}/corpus/${reader}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc)
    message("${out}")
    message(FATAL_ERROR "fuzz_${reader} found a problem")
  endif()
  message("fuzz_${reader}: ${RUNS} runs, clean")
endforeach()
