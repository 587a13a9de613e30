# Cross build for wasm32 with Debian's emscripten 3.1.6, tests run under node (node-run.sh).
# Used by the `wasm` preset. emcc needs NODE_PATH=/usr/share/nodejs in the environment (the
# preset sets it), else its acorn optimizer fails.
include(/usr/share/emscripten/cmake/Modules/Platform/Emscripten.cmake)
# C++ exceptions caught (emscripten's default aborts on throw; the loader reports through them).
set(CMAKE_CXX_FLAGS_INIT "-fexceptions")
# NODERAWFS: the program sees the host's files (scenes, golden hashes) under node.
# ALLOW_MEMORY_GROWTH: worlds larger than the initial 16 MiB heap. EXIT_RUNTIME: main's return
# value becomes node's exit status. -O1 at link time (it follows the build type's -O3 on emcc's
# link line, and the last -O wins): the objects are still clang's -O3, but Binaryen's wasm-opt,
# which took about 40 s a program at -O3 for these test programs, does not run. The shipped page
# (the `web` preset) links at -O3, and the browser checks compare its hashes with x86-64's too.
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-O1 -fexceptions -sNODERAWFS=1 -sALLOW_MEMORY_GROWTH=1 -sEXIT_RUNTIME=1")
set(CMAKE_CROSSCOMPILING_EMULATOR ${CMAKE_CURRENT_LIST_DIR}/node-run.sh CACHE FILEPATH
    "runs a wasm program's .js under node" FORCE)
