# ISODEL_SANITIZE: build every target with sanitizers, for the CI's sanitizer steps
# (tools/qa/sanitizer_checks.sh) and for hunting a crash by hand.
#   -DISODEL_SANITIZE=address,undefined   AddressSanitizer and UndefinedBehaviorSanitizer
#   -DISODEL_SANITIZE=thread              ThreadSanitizer (the threaded mesher)
# A finding stops the program, so a test that trips one fails: ASan never recovers, and UBSan is
# built recoverable only so that ISODEL_SANITIZER_ENV can pass its suppressions of third-party
# headers (cmake/ubsan_suppressions.txt) with halt_on_error=1; LeakSanitizer reads
# cmake/lsan_suppressions.txt (OpenVDB's leaks on a throwing read). Tests and fuzz targets get that
# environment from CTest; set it by hand to run a program outside CTest. The system's
# libraries (OpenVDB, TBB, Boost) are not instrumented: ASan still sees their heap through the
# interposed allocator, TSan sees only the synchronisation they do in inline headers.
set(ISODEL_SANITIZE "" CACHE STRING "Sanitizers for every target: address,undefined | thread | empty")
if(ISODEL_SANITIZE)
  if(NOT ISODEL_SANITIZE MATCHES "^(address,undefined|undefined,address|address|undefined|thread)$")
    message(FATAL_ERROR "ISODEL_SANITIZE must be address,undefined, address, undefined or thread (got ${ISODEL_SANITIZE})")
  endif()
  add_compile_options(-fsanitize=${ISODEL_SANITIZE} -fno-omit-frame-pointer -g1)
  add_link_options(-fsanitize=${ISODEL_SANITIZE})
  set(ISODEL_SANITIZER_ENV
    "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:suppressions=${PROJECT_SOURCE_DIR}/cmake/ubsan_suppressions.txt"
    # verify_asan_link_order=0: libFuzzer's runtime puts libstdc++ before ASan's shared runtime in
    # the fuzz targets' library list; ASan's malloc still comes before libc's, which is what counts.
    "ASAN_OPTIONS=detect_leaks=1:verify_asan_link_order=0"
    "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/cmake/lsan_suppressions.txt"
    "TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=${PROJECT_SOURCE_DIR}/cmake/tsan_suppressions.txt")
  # For what reads corrupt .vdb files (the fuzz targets, the readers' findings): OpenVDB's own
  # code has no frame pointers, so the fast unwinder stops a leak's stack at operator new and the
  # suppressions of its leaks on a throwing read never see an OpenVDB frame. The slow unwinder
  # does; it makes every allocation slower, so only these tests get it.
  set(ISODEL_READER_SANITIZER_ENV ${ISODEL_SANITIZER_ENV})
  list(TRANSFORM ISODEL_READER_SANITIZER_ENV REPLACE "^ASAN_OPTIONS=(.*)$" "ASAN_OPTIONS=\\1:fast_unwind_on_malloc=0")
  if(ISODEL_SANITIZE MATCHES "undefined" AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    # Clang's UBSan runtime for a shared library is linked by the executable; -shared-libsan keeps
    # one runtime for the libraries and the programs that load them.
    # The programs find that runtime through an rpath to Clang's runtime folder.
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-runtime-dir OUTPUT_VARIABLE clang_runtime_dir
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
    add_compile_options(-shared-libsan)
    add_link_options(-shared-libsan "LINKER:-rpath,${clang_runtime_dir}")
  endif()
endif()

# ISODEL_FUZZ: the libFuzzer targets of tests/fuzz (Clang only). Every target is also built with
# -fsanitize=fuzzer-no-link, so the readers report coverage to the fuzzer.
option(ISODEL_FUZZ "Build the libFuzzer targets of tests/fuzz (needs Clang)" OFF)
if(ISODEL_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "ISODEL_FUZZ needs Clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
