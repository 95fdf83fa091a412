# The per-instruction-set builds (cmake/isolated_build.cmake, README "One binary for
# every node"): each isolated object exports only its table, so no copy of a shared
# inline function can be swapped between paths at link time; the scalar object holds no
# AVX instruction and the AVX2 one no AVX-512 instruction, so each runs where its CPU
# check says. The AVX-512 object must hold AVX-512 (zmm) instructions (this check would
# see them); the AVX2 one need not hold ymm ones (under the sanitizers GCC vectorises
# the plain loops of the force kernels no more).
#
# Run by ctest:  cmake -DOBJECTS=<dir> -DSTEM=force_kernels -DTABLE=kForceKernels
#                      -DPATHS=scalar,avx2,avx512 -DNM=nm -DOBJDUMP=objdump
#                      -P tests/check_simd_objects.cmake

foreach(var OBJECTS STEM TABLE PATHS NM OBJDUMP)
    if(NOT ${var})
        message(FATAL_ERROR "check_simd_objects: pass -D${var}=...")
    endif()
endforeach()

set(failures 0)
string(LENGTH "${TABLE}" tableLength)
string(REPLACE "," ";" paths "${PATHS}")
foreach(path ${paths})
    set(object "${OBJECTS}/${STEM}_${path}.o")
    if(NOT EXISTS "${object}")
        message(FATAL_ERROR "check_simd_objects: ${object} is missing")
    endif()
    execute_process(COMMAND "${NM}" --defined-only --extern-only "${object}"
                    OUTPUT_VARIABLE exported RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
        message(FATAL_ERROR "check_simd_objects: ${NM} failed on ${object}")
    endif()
    string(STRIP "${exported}" exported)
    string(REPLACE "\n" ";" exported "${exported}")
    list(LENGTH exported count)
    if(NOT count EQUAL 1 OR NOT exported MATCHES "simd_${path}${tableLength}${TABLE}E$")
        message(SEND_ERROR "check_simd_objects: ${object} exports ${count} symbol(s), "
                           "not only globular::simd_${path}::${TABLE}: ${exported}")
        math(EXPR failures "${failures} + 1")
    endif()
    execute_process(COMMAND "${OBJDUMP}" -d --no-show-raw-insn "${object}"
                    OUTPUT_VARIABLE code RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
        message(FATAL_ERROR "check_simd_objects: ${OBJDUMP} failed on ${object}")
    endif()
    string(REGEX MATCH "%zmm[0-9]+" zmm "${code}")
    string(REGEX MATCH "%ymm[0-9]+" ymm "${code}")
    if(path STREQUAL "scalar" AND (ymm OR zmm))
        message(SEND_ERROR "check_simd_objects: the scalar object uses ${ymm}${zmm}")
        math(EXPR failures "${failures} + 1")
    elseif(path STREQUAL "avx2" AND zmm)
        message(SEND_ERROR "check_simd_objects: the AVX2 object uses ${zmm}")
        math(EXPR failures "${failures} + 1")
    elseif(path STREQUAL "avx512" AND NOT zmm)
        message(SEND_ERROR "check_simd_objects: the AVX-512 object uses no zmm register")
        math(EXPR failures "${failures} + 1")
    endif()
endforeach()
if(failures GREATER 0)
    message(FATAL_ERROR "check_simd_objects: ${failures} problem(s)")
endif()
message(STATUS "check_simd_objects: each ${STEM} build exports only ${TABLE}; scalar has no AVX, AVX2 no AVX-512")
