# -DWARDMAP_SANITIZE=address,undefined  or  -DWARDMAP_SANITIZE=thread  (use a separate build dir).
if(WARDMAP_SANITIZE)
  if(WARDMAP_SANITIZE MATCHES "thread" AND WARDMAP_SANITIZE MATCHES "address")
    message(FATAL_ERROR "WARDMAP_SANITIZE: thread cannot be combined with address")
  endif()
  message(STATUS "wardmap: sanitizers ${WARDMAP_SANITIZE}")
  add_compile_options(-fsanitize=${WARDMAP_SANITIZE} -fno-omit-frame-pointer -g -O1)
  add_link_options(-fsanitize=${WARDMAP_SANITIZE})
  if(WARDMAP_SANITIZE MATCHES "undefined")
    add_compile_options(-fno-sanitize-recover=undefined)
  endif()
endif()

# -DWARDMAP_FUZZ=ON (clang only, its own build dir; scripts/fuzz.sh): every object is instrumented for
# libFuzzer, and tests/fuzz builds one fuzzer per input format. Combine with address,undefined.
option(WARDMAP_FUZZ "Build the libFuzzer targets of tests/fuzz (clang)" OFF)
if(WARDMAP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "WARDMAP_FUZZ needs clang (CXX=clang++): libFuzzer is clang's")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
